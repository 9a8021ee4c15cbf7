-- A headless Neovim session against `lsys lsp` (Neovim 0.7+):
--   LSYS=target/debug/lsys nvim --headless -u NONE -c 'luafile scripts/nvim_lsp_check.lua' grammar.lsys
-- Attaches the server to the buffer, prints the diagnostics, a hover,
-- a definition and the time each took, fixes the first diagnostic with
-- its quick fix and waits for the diagnostics to clear, then quits.
local lsys = os.getenv('LSYS') or 'lsys'
local function ms(t0) return string.format('%.1f ms', (vim.loop.hrtime() - t0) / 1e6) end
local function say(s) io.stdout:write(s .. '\n') end

local t0 = vim.loop.hrtime()
local id = vim.lsp.start_client({ name = 'lsys', cmd = { lsys, 'lsp' }, root_dir = vim.fn.getcwd() })
vim.lsp.buf_attach_client(0, id)
local ok = vim.wait(10000, function() return #vim.diagnostic.get(0) > 0 end, 5)
say('diagnostics after ' .. ms(t0) .. (ok and '' or ' (none arrived)'))
for _, d in ipairs(vim.diagnostic.get(0)) do
  say(string.format('  %d:%d %s [%s]', d.lnum + 1, d.col + 1, d.message:gsub('\n.*', ''), d.code or ''))
end

local function at(line, col)
  return { textDocument = vim.lsp.util.make_text_document_params(0), position = { line = line, character = col } }
end
t0 = vim.loop.hrtime()
local r = vim.lsp.buf_request_sync(0, 'textDocument/hover', at(1, 8), 2000)
for _, res in pairs(r or {}) do
  say('hover on N (' .. ms(t0) .. '): ' .. (res.result and res.result.contents.value:gsub('\n', ' | ') or 'nil'))
end
t0 = vim.loop.hrtime()
r = vim.lsp.buf_request_sync(0, 'textDocument/definition', at(5, 25), 2000)
for _, res in pairs(r or {}) do
  local loc = res.result and res.result[1]
  say('definition of A (' .. ms(t0) .. '): ' .. vim.inspect(loc and loc.uri or res.result))
end

-- Apply the first quick fix and wait for the diagnostics to clear.
local diags = vim.lsp.diagnostic.get_line_diagnostics and vim.lsp.diagnostic.get_line_diagnostics(0, 6) or {}
local params = { textDocument = vim.lsp.util.make_text_document_params(0),
  range = { start = { line = 6, character = 0 }, ['end'] = { line = 6, character = 20 } },
  context = { diagnostics = diags } }
r = vim.lsp.buf_request_sync(0, 'textDocument/codeAction', params, 2000)
for _, res in pairs(r or {}) do
  for _, action in ipairs(res.result or {}) do
    say('quick fix: ' .. action.title)
    vim.lsp.util.apply_workspace_edit(action.edit, 'utf-16')
    t0 = vim.loop.hrtime()
    ok = vim.wait(10000, function() return #vim.diagnostic.get(0) == 0 end, 5)
    say('diagnostics cleared after the edit: ' .. tostring(ok) .. ' (' .. ms(t0) .. ')')
    say('line 7 now: ' .. vim.api.nvim_buf_get_lines(0, 6, 7, false)[1])
    break
  end
end
vim.lsp.stop_client(id)
vim.cmd('qa!')
