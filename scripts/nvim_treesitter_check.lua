-- A headless Neovim session with the tree-sitter grammar (Neovim 0.7+,
-- no plugins): loads the parser built by `tree-sitter build`, parses the
-- buffer, prints any ERROR nodes and the highlight captures of each line
-- from editors/tree-sitter-lsys/queries/highlights.scm, then quits.
--   tree-sitter build -o /tmp/lsys.so        (in editors/tree-sitter-lsys)
--   LSYS_PARSER=/tmp/lsys.so nvim --headless -u NONE \
--     -c 'luafile scripts/nvim_treesitter_check.lua' grammar.lsys
local function say(s) io.stdout:write(s .. '\n') end
local so = os.getenv('LSYS_PARSER') or '/tmp/lsys.so'
local repo = vim.fn.fnamemodify(debug.getinfo(1, 'S').source:sub(2), ':p:h:h')
local ts = vim.treesitter
if ts.language.add then
  ts.language.add('lsys', { path = so })
else
  ts.require_language('lsys', so)
end
local t0 = vim.loop.hrtime()
local parser = ts.get_parser(0, 'lsys')
local tree = parser:parse()[1]
say(string.format('parsed %d lines in %.1f ms', vim.api.nvim_buf_line_count(0), (vim.loop.hrtime() - t0) / 1e6))
local errors = 0
local function walk(node)
  if node:type() == 'ERROR' or node:missing() then
    local r, c = node:start()
    say(string.format('  ERROR at %d:%d', r + 1, c + 1))
    errors = errors + 1
  end
  for child in node:iter_children() do walk(child) end
end
walk(tree:root())
say('errors: ' .. errors)
local text = table.concat(vim.fn.readfile(repo .. '/editors/tree-sitter-lsys/queries/highlights.scm'), '\n')
local parse_query = ts.query.parse or ts.parse_query
local query = parse_query('lsys', text)
local lines = {}
for id, node in query:iter_captures(tree:root(), 0, 0, -1) do
  local r = node:start()
  lines[r] = lines[r] or {}
  table.insert(lines[r], ts.get_node_text and ts.get_node_text(node, 0) .. '=' .. query.captures[id]
    or query.captures[id])
end
for r = 0, vim.api.nvim_buf_line_count(0) - 1 do
  if lines[r] then say(string.format('%3d  %s', r + 1, table.concat(lines[r], ' '))) end
end
vim.cmd('qa!')
