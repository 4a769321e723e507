import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import {
  makeProgressPage,
  mapProgressPage,
  pauseCounter,
  PROGRESS_PAGE_BYTES,
  readPageProgress,
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

  it('gives the supervisor the last progress the session stored, its text whole or cut at a character', function () {
    if (process.platform === 'win32') this.skip();
    const file = path.join(temporaryFolder(), 'progress-page');
    makeProgressPage(file);
    assert.equal(readPageProgress(file), undefined, 'a page of zeros says nothing');
    const session = mapProgressPage(file);
    assert.ok(session);
    session.start(0.05);
    session.steps(60);
    session.progress({ time: 3.05, what: 'Event ÜberholEvent standby' });
    assert.deepEqual(readPageProgress(file), { time: 3.05, what: 'Event ÜberholEvent standby' });
    session.progress({ time: 3.1, what: 'Act A running' });
    assert.deepEqual(readPageProgress(file), { time: 3.1, what: 'Act A running' }, 'a shorter text after a longer one');
    assert.equal(readProgressPage(file)?.toFixed(2), '3.00', 'the step count is left alone');
    // Longer than the page holds: cut before the character that does not fit whole (ü is two bytes).
    session.progress({ time: 4, what: `${'x'.repeat(PROGRESS_PAGE_BYTES - 64 - 1)}ü` });
    assert.equal(readPageProgress(file)?.what, 'x'.repeat(PROGRESS_PAGE_BYTES - 64 - 1));
    assert.equal(readPageProgress(path.join(path.dirname(file), 'absent')), undefined);
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
