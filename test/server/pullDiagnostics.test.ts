import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';
import { Diagnostic } from 'vscode-languageserver/node';
import { main } from '../../server/src/cli';
import { problemCodeOf } from '../support/diagnostics';
import { withoutSchema } from '../support/fixtures';
import { MAIN, mainWithKeys, withDuplicateGroups } from './fixtures/scenarios';
import { useServer } from './harness';

interface WorkspaceReport {
  items: { uri: string; kind: string; resultId?: string; items?: Diagnostic[] }[];
}

/** `file:line:code:severity` of every problem, from `check --format json` or from workspace/diagnostic. */
async function checkLines(root: string): Promise<string[]> {
  const printed: string[] = [];
  // The harness turns the server's schema check off (minimal fixtures), so check runs the same way.
  await main(withoutSchema(['check', root, '--format', 'json', '--root', root]), {
    out: (text) => printed.push(text),
    err: () => undefined,
  });
  const report = JSON.parse(printed.join('')) as { problems: { file: string; line: number; code: string; severity: string }[] };
  return report.problems.map((problem) => `${path.resolve(problem.file)}:${problem.line}:${problem.code}:${problem.severity}`).sort();
}

function reportLines(report: WorkspaceReport): string[] {
  const severityName = ['', 'error', 'warning', 'information'];
  return report.items
    .flatMap((file) =>
      (file.items ?? []).map(
        (diagnostic) =>
          `${fileURLToPath(file.uri)}:${diagnostic.range.start.line + 1}:${problemCodeOf(diagnostic)}:${severityName[diagnostic.severity ?? 0]}`,
      ),
    )
    .sort();
}

describe('language server: workspace-wide pull diagnostics (JSON-RPC)', function () {
  const server = useServer(
    {
      'simple.xosc': withDuplicateGroups(),
      'main.xosc': MAIN,
      'clean.xosc': mainWithKeys(['<ParameterReference key="AbsoluteTargetSpeed.value" value="9"/>']),
      'unopened/broken.xosc': mainWithKeys(['<ParameterReference key="nosuchkey" value="1"/>']).replace(
        'scenarioFileName="simple.xosc"',
        'scenarioFileName="../simple.xosc"',
      ),
    },
    'clean.xosc',
    { pullDiagnostics: true },
  );

  it('reports every scenario file of the workspace as check does, open or not', async function () {
    const report = await server.client.request<WorkspaceReport>('workspace/diagnostic', { previousResultIds: [] });
    const lines = reportLines(report);
    assert.ok(
      lines.some((line) => line.includes(`${path.sep}unopened${path.sep}broken.xosc:`) && line.includes(':unknown-key:error')),
      lines.join('\n'),
    );
    assert.deepEqual(lines, await checkLines(server.root));
  });

  it('answers unchanged for what did not change, and pushes nothing', async function () {
    const first = await server.client.request<WorkspaceReport>('workspace/diagnostic', { previousResultIds: [] });
    const again = await server.client.request<WorkspaceReport>('workspace/diagnostic', {
      previousResultIds: first.items.map((item) => ({ uri: item.uri, value: item.resultId })),
    });
    assert.ok(again.items.every((item) => item.kind === 'unchanged'));
    assert.equal(server.client.diagnostics.size, 0, 'a pulling client gets no diagnostics pushed');
  });

  it("pulls an open document's diagnostics, with those other files place in it, and asks for a new pull after an edit", async function () {
    const uri = await server.client.openFile(path.join(server.root, 'simple.xosc'));
    const report = await server.client.request<{ kind: string; items: Diagnostic[] }>('textDocument/diagnostic', { textDocument: { uri } });
    // The duplicate Brake is reported because main.xosc and clean.xosc refer to that name.
    assert.deepEqual(report.items.map((diagnostic) => problemCodeOf(diagnostic)).sort(), [
      'duplicate-group',
      'unknown-parameter-attribute',
    ]);
    const before = server.client.refreshes;
    await server.client.change(uri, [{ range: { start: { line: 0, character: 0 }, end: { line: 0, character: 0 } }, text: ' ' }]);
    await server.client.until(() => server.client.refreshes > before || undefined, 'a workspace/diagnostic/refresh');
    await server.client.close(uri);
  });
});
