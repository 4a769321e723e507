// Builds esmini with ../shared/esmini/build.sh for `npm start`, telling how far the build is: the script itself
// writes make's output only to DEST/build.log, so without this a first start is silent for many minutes.
import { spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';

/**
 * The last percentage make has printed (`[ 42%] Building CXX object ...`), or undefined before the first.
 * @param {string} logText
 * @returns {number | undefined}
 */
export function buildPercent(logText) {
  let percent;
  for (const match of logText.matchAll(/^\[\s*(\d{1,3})%\]/gm)) percent = Number(match[1]);
  return percent;
}

/**
 * Runs `bash buildScript dest` and calls `report` with a line at each 10 % make passes (and at least every
 * `quietMs` while it stays at one step), then once at the end. Resolves to the esmini program, or undefined
 * when the build failed (its own messages, on standard error, say why) or was stopped by `signal`, which ends
 * the build's whole process group (bash, make and the compilers), so that nothing builds on unseen.
 * @param {{ buildScript: string, dest: string, report: (line: string) => void, pollMs?: number, quietMs?: number, signal?: AbortSignal }} options
 * @returns {Promise<string | undefined>}
 */
export function buildEsmini({ buildScript, dest, report, pollMs = 2000, quietMs = 60_000, signal }) {
  const program = path.join(dest, 'bin', 'esmini');
  const log = path.join(dest, 'build.log');
  const started = Date.now();
  let reported = -1;
  let reportedAt = started;
  const elapsed = () => {
    const seconds = Math.round((Date.now() - started) / 1000);
    return seconds < 60 ? `${seconds} s` : `${Math.floor(seconds / 60)} min ${seconds % 60} s`;
  };
  const poll = () => {
    let percent;
    try {
      percent = buildPercent(fs.readFileSync(log, 'utf8'));
    } catch {
      return; // not started yet, or an earlier build's log about to be replaced
    }
    if (percent === undefined) return;
    const now = Date.now();
    if (Math.floor(percent / 10) > Math.floor(reported / 10) || now - reportedAt >= quietMs) {
      report(`esmini build: ${percent} % after ${elapsed()} (log: ${log})`);
      reported = percent;
      reportedAt = now;
    }
  };
  return new Promise((resolve) => {
    if (signal?.aborted) return resolve(undefined);
    // An earlier build's log would report its 100 % at once: only a log written by this build counts (read before it starts).
    const earlierLog = fs.existsSync(log) ? fs.statSync(log).mtimeMs : undefined;
    const child = spawn('bash', [buildScript, dest], { stdio: ['ignore', 'ignore', 'inherit'], detached: true });
    const stop = () => {
      try {
        process.kill(-(/** @type {number} */ (child.pid)), 'SIGTERM');
      } catch {
        // already ended
      }
    };
    signal?.addEventListener('abort', stop, { once: true });
    const pollThisBuild = () => {
      if (earlierLog === undefined || (fs.existsSync(log) && fs.statSync(log).mtimeMs !== earlierLog)) poll();
    };
    const timer = setInterval(pollThisBuild, pollMs);
    const finish = (/** @type {boolean} */ ok) => {
      clearInterval(timer);
      signal?.removeEventListener('abort', stop);
      // The log's last lines (make's 100 %) may land after the last poll: read them once more before the closing line.
      if (!signal?.aborted) pollThisBuild();
      const built = ok && fs.existsSync(program);
      if (signal?.aborted) report(`esmini build stopped after ${elapsed()}; the next npm start builds it again`);
      else if (reported >= 0) report(built ? `esmini built in ${elapsed()}: ${program}` : `esmini did not build after ${elapsed()}`);
      resolve(built ? program : undefined);
    };
    child.on('error', () => finish(false));
    child.on('exit', (code) => finish(code === 0));
  });
}
