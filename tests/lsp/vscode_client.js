// Microsoft's own LSP client library (vscode-jsonrpc and vscode-languageserver-protocol, the
// ones VS Code's extensions use) against `seqc lsp --stdio`: initialize, open a copy of an
// example with `tme:` for `time:`, check the published diagnostic exactly, fix it with an
// incremental change, see the diagnostics clear, then shutdown and exit with status 0.
//
// Usage: node vscode_client.js SEQC EXAMPLE.yaml   (NODE_PATH: where the packages are)
// The connection is vscode-jsonrpc's; the protocol package gives the method names and constants
// (by name, as it carries its own copy of vscode-jsonrpc whose message types would not mix).
'use strict';
const assert = require('assert');
const cp = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');
const rpc = require('vscode-jsonrpc/node');
const lsp = require('vscode-languageserver-protocol');

async function main() {
  const [seqc, example] = process.argv.slice(2);
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'seqc-lsp-'));
  const file = path.join(dir, 'walk.yaml');
  const lines = fs.readFileSync(example, 'utf8').split('\n');
  lines[9] = lines[9].replace('time:', 'tme:');
  const text = lines.join('\n');
  fs.writeFileSync(file, text);
  const uri = 'file://' + file;

  const server = cp.spawn(seqc, ['lsp', '--stdio'], { stdio: ['pipe', 'pipe', 'inherit'] });
  const exited = new Promise((resolve) => server.on('exit', (code) => resolve(code)));
  const connection = rpc.createMessageConnection(
    new rpc.StreamMessageReader(server.stdout), new rpc.StreamMessageWriter(server.stdin));
  const published = [];
  let notify = () => {};
  connection.onNotification(lsp.PublishDiagnosticsNotification.method, (params) => {
    published.push(params);
    notify();
  });
  connection.listen();
  const nextDiagnostics = (timeoutMs = 10000) => new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error('no publishDiagnostics')), timeoutMs);
    const check = () => {
      const i = published.findIndex((p) => p.uri === uri);
      if (i < 0) return;
      clearTimeout(timer);
      resolve(published.splice(i, 1)[0].diagnostics);
    };
    notify = check;
    check();
  });

  const init = await connection.sendRequest(lsp.InitializeRequest.method, {
    processId: process.pid, rootUri: 'file://' + dir, capabilities: {},
  });
  assert.deepStrictEqual(init.serverInfo.name, 'seqc');
  assert.deepStrictEqual(init.capabilities.textDocumentSync,
    { openClose: true, change: lsp.TextDocumentSyncKind.Incremental, save: { includeText: false } });
  await connection.sendNotification(lsp.InitializedNotification.method, {});

  await connection.sendNotification(lsp.DidOpenTextDocumentNotification.method, {
    textDocument: { uri, languageId: 'yaml', version: 1, text },
  });
  assert.deepStrictEqual(await nextDiagnostics(), [{
    range: { start: { line: 9, character: 4 }, end: { line: 9, character: 7 } },
    severity: lsp.DiagnosticSeverity.Error,
    code: 'unknown-key',
    source: 'seqc',
    message: "unknown key 'tme' in a move step; did you mean 'time'?",
  }]);

  // An unknown request is an error the library reports as such.
  await assert.rejects(connection.sendRequest('seqc/noSuchMethod', {}),
    (e) => e.code === rpc.ErrorCodes.MethodNotFound);

  await connection.sendNotification(lsp.DidChangeTextDocumentNotification.method, {
    textDocument: { uri, version: 2 },
    contentChanges: [{ range: { start: { line: 9, character: 5 }, end: { line: 9, character: 5 } },
      text: 'i' }],
  });
  assert.deepStrictEqual(await nextDiagnostics(), []);

  // Musical time where the text is written: a dance at 120 bpm in 4/4 (a beat 500 ms, a bar
  // 2 s). Its steps start at 0, 2 s (bar 2), 3 s (bar 2 beat 3) and 3.5 s (bar 2 beat 4).
  const beatFile = path.join(dir, 'beat.yaml');
  const beatUri = 'file://' + beatFile;
  const beatText = [
    'robot: xarm', 'tempo: 120', 'meter: 4/4', 'poses:', '  up: {base: 700}', 'sequence:',
    '  - move: home', '    time: 2s', '  - move: up', '    time: 1s',
    '  - move: {base: 300}', '    time: 500ms', '  - move: up', '    time: 250ms', '',
  ].join('\n');
  fs.writeFileSync(beatFile, beatText);
  await connection.sendNotification(lsp.DidOpenTextDocumentNotification.method, {
    textDocument: { uri: beatUri, languageId: 'yaml', version: 1, text: beatText },
  });
  const hints = await connection.sendRequest(lsp.InlayHintRequest.method, {
    textDocument: { uri: beatUri },
    range: { start: { line: 0, character: 0 }, end: { line: 14, character: 0 } },
  });
  const labels = {};
  for (const h of hints) labels[h.position.line] = h.label;
  assert.deepStrictEqual(labels, {
    6: '0.000 s \u00B7 1:1 \u00B7 2.000 s',
    8: '2.000 s \u00B7 2:1 \u00B7 1.000 s',
    10: '3.000 s \u00B7 2:3 \u00B7 500 ms',
    12: '3.500 s \u00B7 2:4 \u00B7 250 ms',
  });
  // `up` on line 12 is defined on line 4, at its name.
  const definition = await connection.sendRequest(lsp.DefinitionRequest.method, {
    textDocument: { uri: beatUri }, position: { line: 12, character: 11 },
  });
  const target = Array.isArray(definition) ? definition[0] : definition;
  assert.strictEqual(target.uri, beatUri);
  assert.strictEqual(target.range.start.line, 4);
  assert.strictEqual(target.range.start.character, 2);
  // Hovering the pose's use shows its value.
  const hover = await connection.sendRequest(lsp.HoverRequest.method, {
    textDocument: { uri: beatUri }, position: { line: 12, character: 11 },
  });
  const hoverText = JSON.stringify(hover.contents);
  assert.ok(hoverText.includes('base') && hoverText.includes('700'), hoverText);

  await connection.sendRequest(lsp.ShutdownRequest.method);
  await connection.sendNotification(lsp.ExitNotification.method);
  assert.strictEqual(await exited, 0);
  connection.dispose();
  fs.rmSync(dir, { recursive: true });
  console.log('1 passed, 0 failed');
}

main().catch((e) => {
  console.error(e);
  console.log('0 passed, 1 failed');
  process.exit(1);
});
