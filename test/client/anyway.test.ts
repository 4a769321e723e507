import * as assert from 'node:assert/strict';
import {
  namedErrors,
  runAnywayQuestion,
  runBlockingErrors,
  runLensTitles,
  writeAnywayQuestion,
  writtenAnywayNote,
} from '../../client/src/anyway';
import type { ProblemSummary, RunEsminiResult } from '../../common/src/protocol';

const cutIn = 'file:///work/esmini/cut-in.xosc';

function problem(message: string, line: number, severity: ProblemSummary['severity'] = 'error', uri = cutIn): ProblemSummary {
  return { uri, line, character: 4, severity, message };
}

function refused(fields: Partial<RunEsminiResult>): RunEsminiResult {
  return {
    outcome: 'not-flattened',
    message: 'the scenario has 1 error; nothing was run',
    uri: cutIn,
    problems: [],
    flattenProblems: [problem("unknown name 'BrakeCondition_HWT'", 161), problem('deprecated', 10, 'warning')],
    esminiFindings: [],
    log: '',
    duration: 30,
    timeStep: 0.05,
    seed: 1,
    wallMs: 5,
    ...fields,
  };
}

describe('client: Write Anyway and Run Anyway', () => {
  it('names the errors (not the warnings) with their file and line, the first three and how many more', () => {
    const problems = [
      problem('a', 0),
      problem('w', 1, 'warning'),
      problem('b', 1, 'error', 'file:///w/lane%20change.xosc'),
      problem('c', 2),
      problem('d', 3),
      problem('e', 4),
    ];
    assert.equal(namedErrors(problems), 'a (cut-in.xosc:1); b (lane change.xosc:2); c (cut-in.xosc:3); and 2 more');
  });

  it("Flatten's question counts every error, not only overrides, and names the key an override got wrong", () => {
    const problems = [
      problem("key 'LaneChangeActionDynamic.value' matches no attribute listed in a parameterAttributes of group 'CutIn'", 12),
      problem("unknown name 'x'", 40),
    ];
    const question = writeAnywayQuestion('Flatten to .xosc', problems);
    assert.match(question, /^Flatten to \.xosc: nothing was written, because of 2 errors: key 'LaneChangeActionDynamic\.value'/);
    assert.match(question, /Write anyway.*\(as --force does\)\?$/);
    assert.equal(writtenAnywayNote(problems.slice(0, 1)), ' (written anyway despite 1 error)');
  });

  it('offers Run Anyway only for a run refused for its errors alone', () => {
    assert.match(
      runAnywayQuestion(refused({ forcible: true })) ?? '',
      /^Run in esmini: the scenario has 1 error; nothing was run: unknown name 'BrakeCondition_HWT' \(cut-in\.xosc:162\)\. Run anyway/,
    );
    // A refusal that forcing cannot help (a missing group), and runs that happened, get no offer.
    assert.equal(runAnywayQuestion(refused({})), undefined);
    assert.equal(runAnywayQuestion(refused({ outcome: 'ok', forcible: true })), undefined);
    assert.equal(runAnywayQuestion(refused({ outcome: 'errors' })), undefined);
  });

  it('shows the Run Anyway CodeLens beside Run in esmini only while the file has errors', () => {
    assert.deepEqual(runLensTitles(0), [{ title: '▶ Run in esmini', force: false }]);
    assert.deepEqual(runLensTitles(2), [
      { title: '▶ Run in esmini', force: false },
      { title: '▶ Run Anyway (2 errors)', force: true },
    ]);
  });

  it("Run Anyway counts the errors a run in esmini is refused for: not esmini's own messages, nor what the selected simulator refuses (cut-in.xosc under CARLA: 1, not 6)", () => {
    const carla = (value: string) => ({ isError: true, source: 'modular2simple', code: value });
    const diagnostics = [
      { isError: true, source: 'modular2simple', code: { value: 'catalog-directory', target: 'https://example.org' } },
      carla('simulator'),
      carla('simulator'),
      carla('simulator'),
      carla('simulator'),
      carla('simulator'),
      { isError: true, source: 'esmini', code: 'esmini' },
      { isError: false, source: 'modular2simple', code: 'out-of-range' },
      { isError: true, source: 'modular2simple', code: 'simulator-value' },
    ];
    assert.equal(runBlockingErrors(diagnostics), 1);
    assert.deepEqual(
      runLensTitles(runBlockingErrors(diagnostics)).map((lens) => lens.title),
      ['▶ Run in esmini', '▶ Run Anyway (1 error)'],
    );
    assert.equal(runBlockingErrors(diagnostics.slice(1)), 0);
  });
});
