// The VS Code client of `lsys lsp`: starts the server for .lsys and .l
// files (the command from the `lsys.path` setting) and restarts it when
// the setting changes.
const vscode = require('vscode');
const { LanguageClient } = require('vscode-languageclient/node');

let client;

function start() {
  const config = vscode.workspace.getConfiguration('lsys');
  const server = { command: config.get('path', 'lsys'), args: ['lsp', ...config.get('args', [])] };
  client = new LanguageClient('lsys', 'lsys', server, {
    documentSelector: [
      { scheme: 'file', language: 'lsys' },
      { scheme: 'file', language: 'cpfg' },
      { scheme: 'untitled', language: 'lsys' },
    ],
  });
  return client.start();
}

function activate(context) {
  context.subscriptions.push(
    vscode.workspace.onDidChangeConfiguration(async (e) => {
      if (e.affectsConfiguration('lsys') && client) {
        await client.stop();
        await start();
      }
    }),
  );
  return start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
