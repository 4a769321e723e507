import * as assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { MAIN, SIMPLE } from './fixtures/scenarios';
import { at } from '../support/cursor';
import { repoRoot } from '../support/paths';
import { SERVER_WAIT_MS } from '../support/wait';
import { temporaryWorkspace } from '../support/workspace';

const serverBundle = path.join(repoRoot, 'dist', 'server.js');

function hasNeovim(): boolean {
  return spawnSync('nvim', ['--version'], { encoding: 'utf8' }).status === 0;
}

interface NeovimReport {
  errors: string[];
  diagnostics: { lnum: number; col: number; message: string; severity: number; code: string | null }[];
  definition: { uri?: string; targetUri?: string; range?: { start: { line: number; character: number } } }[] | null;
  hover: { contents: { kind: string; value: string } } | null;
  completion: { label: string }[] | { items: { label: string }[] } | null;
}

/** The codes of main.xosc's diagnostics (without pkg.mosc beside it, pkg.xosc is a second missing file). */
const EXPECTED_CODES = ['missing-file', 'missing-file', 'no-default', 'unknown-group', 'unknown-key'];

/** Lua for Neovim 0.7: start the built server over stdio, open the file, ask, write JSON, quit. */
function probe(
  root: string,
  file: string,
  output: string,
  positions: Record<'definition' | 'hover' | 'completion', { line: number; character: number }>,
): string {
  const lua = (value: unknown) => JSON.stringify(value).replace(/\[/g, '{').replace(/\]/g, '}');
  return `
local out = { errors = {} }
local client_id = vim.lsp.start_client({
  name = 'modular2simple',
  -- Errors the server logs (MessageType.Error = 1) fail the test, as in the JSON-RPC harness.
  handlers = {
    ['window/logMessage'] = function(_, result)
      if result and result.type == 1 then table.insert(out.errors, result.message) end
    end,
  },
  cmd = { ${lua(process.execPath)}, ${lua(serverBundle)}, '--stdio' },
  root_dir = ${lua(root)},
  workspace_folders = { { uri = vim.uri_from_fname(${lua(root)}), name = 'fixtures' } },
  -- The shared fixtures are minimal, not schema-valid: the schema check is tested elsewhere.
  init_options = { schema = { version = 'off' } },
})
vim.cmd('edit ' .. vim.fn.fnameescape(${lua(file)}))
local bufnr = vim.api.nvim_get_current_buf()
vim.lsp.buf_attach_client(bufnr, client_id)
-- All of them: a first publication may come before the server has read the other files.
vim.wait(${SERVER_WAIT_MS}, function() return #vim.diagnostic.get(bufnr) >= ${EXPECTED_CODES.length} end, 50)
out.diagnostics = {}
for _, d in ipairs(vim.diagnostic.get(bufnr)) do
  local code = d.code or (d.user_data and d.user_data.lsp and d.user_data.lsp.code) or vim.NIL
  table.insert(out.diagnostics, { lnum = d.lnum, col = d.col, message = d.message, severity = d.severity, code = code })
end
local function ask(method, line, character)
  local params = { textDocument = { uri = vim.uri_from_bufnr(bufnr) }, position = { line = line, character = character } }
  local responses = vim.lsp.buf_request_sync(bufnr, method, params, ${SERVER_WAIT_MS})
  local response = responses and responses[client_id]
  return (response and response.result) or vim.NIL
end
out.definition = ask('textDocument/definition', ${positions.definition.line}, ${positions.definition.character})
out.hover = ask('textDocument/hover', ${positions.hover.line}, ${positions.hover.character})
out.completion = ask('textDocument/completion', ${positions.completion.line}, ${positions.completion.character})
local file = io.open(${lua(output)}, 'w')
file:write(vim.fn.json_encode(out))
file:close()
vim.lsp.stop_client(client_id)
vim.cmd('qa!')
`;
}

describe('the built server driven by Neovim (a second LSP client)', function () {
  // The build, then Neovim and the server, on a machine that may be loaded (2 cores at a load of 25): generous.
  this.timeout(4 * SERVER_WAIT_MS);
  let report: NeovimReport;
  let root: string;

  before(function () {
    if (!hasNeovim()) {
      if (process.env.M2S_REQUIRE_NVIM === '1') throw new Error('M2S_REQUIRE_NVIM=1 but nvim is not installed');
      console.log('    (skipped: nvim is not installed; apt-get install neovim)');
      this.skip();
    }
    execFileSync(process.execPath, [path.join(repoRoot, 'scripts', 'build.mjs')], { cwd: repoRoot, stdio: 'inherit' });
    root = temporaryWorkspace({ 'simple.xosc': SIMPLE, 'main.xosc': MAIN });
    const output = path.join(root, 'report.json');
    const script = path.join(root, 'probe.lua');
    fs.writeFileSync(
      script,
      probe(root, path.join(root, 'main.xosc'), output, {
        definition: at(MAIN, 'maneuverGroupName="Br|ake"'),
        hover: at(MAIN, 'key="AbsoluteTargetSpeed.val|ue"'),
        completion: at(MAIN, 'maneuverGroupName="|Brake"'),
      }),
    );
    const run = spawnSync('nvim', ['--headless', '--clean', '-u', 'NONE', '-c', `luafile ${script}`], {
      cwd: root,
      encoding: 'utf8',
      timeout: 3 * SERVER_WAIT_MS,
      env: { ...process.env, HOME: root, XDG_STATE_HOME: root, XDG_DATA_HOME: root },
    });
    assert.ok(fs.existsSync(output), `nvim wrote no report (status ${run.status}): ${run.stderr}${run.stdout}`);
    report = JSON.parse(fs.readFileSync(output, 'utf8')) as NeovimReport;
  });

  after(function () {
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('the server logged no error', function () {
    assert.deepEqual(report.errors, []);
  });

  it('receives the diagnostics', function () {
    const codes = report.diagnostics.map((diagnostic) => diagnostic.code).sort();
    assert.deepEqual(codes, EXPECTED_CODES);
    const unknownKey = report.diagnostics.find((diagnostic) => diagnostic.code === 'unknown-key');
    assert.deepEqual(unknownKey && { line: unknownKey.lnum, character: unknownKey.col }, at(MAIN, 'key="|dela"'));
  });

  it('goes to a definition in another file', function () {
    const [location] = report.definition ?? [];
    assert.ok(location, JSON.stringify(report.definition));
    assert.equal(location.uri ?? location.targetUri, `file://${path.join(root, 'simple.xosc')}`);
    assert.deepEqual(location.range?.start, at(SIMPLE, '<ManeuverGroup name="|Brake"'));
  });

  it('shows a hover', function () {
    assert.match(report.hover?.contents.value ?? '', /takes effect: `7` \(this key\)/);
  });

  it('completes group names', function () {
    const items = Array.isArray(report.completion) ? report.completion : (report.completion?.items ?? []);
    assert.deepEqual(
      items.map((item) => item.label),
      ['Brake', 'Wait'],
    );
  });
});
