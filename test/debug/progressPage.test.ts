import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import {
  makeProgressPage,
  mapProgressPage,
  pauseCounter,
  PROGRESS_PAGE_BYTES,
  readProgressPage,
} from '../../server/src/debug/progressPage';
import { temporaryFolder } from '../support/temporaryDirectory';

describe('debug session progress page', () => {
  it('gives the supervisor the time the session stored through its mapping, and nothing for a page never written', function () {
    if (process.platform === 'win32') this.skip();
    const file = path.join(temporaryFolder(), 'progress-page');
    makeProgressPage(file);
    assert.equal(fs.statSync(file).size, PROGRESS_PAGE_BYTES);
    assert.equal(readProgressPage(file), undefined, 'a page of zeros says nothing');
    const counter = mapProgressPage(file);
    assert.ok(counter, 'the page maps');
    counter.start(0.05);
    counter.steps(103);
    // Read from the file, as the supervisor does after the session died: what was stored in memory, no write call.
    assert.equal(readProgressPage(file)?.toFixed(2), '5.15');
    counter.steps(104);
    assert.equal(readProgressPage(file)?.toFixed(2), '5.20');
    assert.equal(readProgressPage(path.join(path.dirname(file), 'absent')), undefined);
  });

  it("shows the session each pause request the supervisor counts into the file, through the session's mapping", function () {
    if (process.platform === 'win32') this.skip();
    const file = path.join(temporaryFolder(), 'progress-page');
    makeProgressPage(file);
    const session = mapProgressPage(file);
    assert.ok(session);
    session.start(0.05);
    assert.equal(session.pauseRequests(), 0);
    const countPause = pauseCounter(file);
    countPause();
    assert.equal(session.pauseRequests(), 1, 'a write to the file is seen in the mapping, no read call');
    countPause();
    assert.equal(session.pauseRequests(), 2);
    // The session's own slots are left alone.
    session.steps(20);
    assert.equal(readProgressPage(file)?.toFixed(2), '1.00');
  });
});
