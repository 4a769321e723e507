import * as assert from 'node:assert/strict';
import { batchFailure, limitedRuns, otherBatchInResults } from '../../client/src/variations/batchFailure';

describe('Run Variations: why a batch did not end well, for its notification', () => {
  it("names the runs esmini refused with esmini's reason, the criteria failed, or the problem that stopped the batch", () => {
    const refused = [
      '[1/3] 7: error: esmini did not run the scenario (exit code 255): Failed to locate OpenDRIVE file e6mini.xodr',
      '3 runs (0 ok, 0 limit, 0 timeout, 3 error; 0 with a collision); results in /w/results/results.csv, …',
      'modular2simple: error: 3 of 3 runs failed in esmini (status error); the column reason of /w/results/results.csv says why for each:',
      '  #7, #14, #20: esmini did not run the scenario (exit code 255): Failed to locate OpenDRIVE file e6mini.xodr',
    ];
    assert.equal(
      batchFailure(refused),
      '3 of 3 runs failed in esmini (status error); the column reason of /w/results/results.csv says why for each: #7, #14, #20: esmini did not run the scenario (exit code 255): Failed to locate OpenDRIVE file e6mini.xodr',
    );
    assert.equal(
      batchFailure(refused, { path: '/w/results/results.csv', name: 'results/results.csv' }),
      '3 of 3 runs failed in esmini (status error); the column reason of results/results.csv says why for each: #7, #14, #20: esmini did not run the scenario (exit code 255): Failed to locate OpenDRIVE file e6mini.xodr',
      'the whole path gives way to the name the editor shows',
    );
    assert.equal(
      batchFailure(['8 runs (8 ok, …)', 'modular2simple: 2 runs failed the criteria (collision): #0: collision; #3: collision']),
      '2 runs failed the criteria (collision): #0: collision; #3: collision',
    );
    assert.equal(
      batchFailure([
        "follow.xosc:26:27: error: the VehicleCatalog directory 'gone' does not exist beside this file nor in SCENARIO_PATH, so …",
        '  hint: correct the path',
      ]),
      "follow.xosc:26:27: error: the VehicleCatalog directory 'gone' does not exist beside this file nor in SCENARIO_PATH, so …",
    );
    assert.equal(batchFailure(['modular2simple: error: esmini is not at /x: …']), 'esmini is not at /x: …');
    assert.equal(batchFailure(['12 runs (12 ok, …)']), undefined);
  });
});

describe('Run Variations: a results folder holding another batch, for the question whether to replace it', () => {
  it('says how the batches differ in words, and nothing for any other end', () => {
    assert.equal(
      otherBatchInResults([
        'd.xosc: warning: …',
        "modular2simple: error: /w/d.results/results.csv holds another batch's results (it differs in scenarioSha256, duration); use another --results folder",
      ]),
      "it differs in the scenario's text, the duration limit",
    );
    assert.equal(
      otherBatchInResults([
        "modular2simple: error: /w/d.results/results.csv holds another batch's results (its columns are not index,status,…); use another --results folder",
      ]),
      'its columns differ',
    );
    assert.equal(otherBatchInResults(['modular2simple: error: 3 of 3 runs failed in esmini (status error); …']), undefined);
  });
});

describe('Run Variations: how many runs the time limit stopped, for the notification naming its setting', () => {
  it("reads the CLI's summary line, and nothing without one", () => {
    const printed = ['[1/4] 0: ok', '4 runs (1 ok, 2 limit, 0 timeout, 1 error; 0 with a collision); results in /w/r/results.csv, …'];
    assert.equal(limitedRuns(printed), 2);
    assert.equal(limitedRuns(['1 run (0 ok, 1 limit, 0 timeout, 0 error; 0 with a collision)']), 1);
    assert.equal(limitedRuns(['12 runs (12 ok, 0 limit, 0 timeout, 0 error; 0 with a collision)']), 0);
    assert.equal(limitedRuns(['modular2simple: error: esmini is not at /x']), undefined);
  });
});
