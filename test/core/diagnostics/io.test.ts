import * as assert from 'node:assert/strict';
import { IO, ioWording, notUnpackedPackageWording, packFolderWording } from '../../../server/src/core/diagnostics/io';
import { analysisProblemsOf } from './support';

describe('diagnostics: io', () => {
  it('words what pack cannot read', () => {
    assert.deepEqual(packFolderWording('scenarios'), {
      severity: 'error',
      code: 'io',
      message: "scenarios is a folder; pack a folder with 'modular2simple pack FOLDER -o OUT.mosc'",
      hint: undefined,
    });
    assert.deepEqual(notUnpackedPackageWording('out'), {
      severity: 'error',
      code: 'io',
      message: 'out holds no main.xosc, so it is not an unpacked package',
      hint: 'a package folder must hold main.xosc',
    });
    assert.equal(IO.severity, 'error');
  });

  it('is what an analysis of a file that is not there reports', async () => {
    const problems = await analysisProblemsOf({ 'other.xosc': '<OpenSCENARIO/>' }, 'main.xosc');
    assert.deepEqual(
      problems.map((problem) => [problem.code, problem.severity]),
      [['io', 'error']],
    );
    assert.equal(ioWording(problems[0].message).message, problems[0].message);
  });
});
