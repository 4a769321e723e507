// Edit to live preview: the time from sending an edit to the language server until its answer to
// the preview request (flattened text and line map) arrives, as the VS Code client asks right after
// the edit is sent (client/src/preview.ts, no debounce).

const now = () => Number(process.hrtime.bigint()) / 1e6;

/**
 * @param {string} text
 * @param {string} needle
 * @param {number} nth
 */
function positionAfter(text, needle, nth) {
  let index = -1;
  for (let i = 0; i <= nth; i++) index = text.indexOf(needle, index + 1);
  if (index < 0) throw new Error(`${needle} not found`);
  const before = text.slice(0, index + needle.length);
  return { line: before.split('\n').length - 1, character: before.length - (before.lastIndexOf('\n') + 1) };
}

/**
 * Changes the first character of a value after `needle` (cycling through its occurrences) to a
 * digit, then asks for the preview; `version` is the document's current version. Answers the
 * times (ms) and the next free version; fails when a preview lacks text.
 * @param {import('vscode-languageserver-protocol').ProtocolConnection} connection
 * @param {string} uri
 * @param {string} text
 * @param {string} needle
 * @param {{ samples: number, version: number }} options
 */
export async function previewLatency(connection, uri, text, needle, { samples, version }) {
  const occurrences = text.split(needle).length - 1;
  const times = [];
  for (let i = 0; i < samples; i++) {
    const position = positionAfter(text, needle, (i * 37) % occurrences);
    const started = now();
    await connection.sendNotification('textDocument/didChange', {
      textDocument: { uri, version: ++version },
      contentChanges: [
        { range: { start: position, end: { line: position.line, character: position.character + 1 } }, text: String(1 + (i % 9)) },
      ],
    });
    const result = await connection.sendRequest('modular2simple/preview', { uri });
    times.push(now() - started);
    if (result.text === null) throw new Error(`no preview text: ${JSON.stringify(result.problems.slice(0, 3))}`);
    if (result.lines.length === 0) throw new Error('no line map');
  }
  return { times, version };
}
