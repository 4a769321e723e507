import { ChildProcess, spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {
  makeProgressPage,
  pauseCounter,
  PROGRESS_PAGE_ENV,
  readPageProgress,
  readProgressPage,
  type SessionProgress,
} from './progressPage';
import { shownFixed } from './watchExpression';

/*
 * The debug adapter's outer process (dist/debugAdapter.js as the editor starts it): it runs the session (adapter.ts),
 * and with it esmini's library, in a child of its own and passes the Debug Adapter Protocol through unchanged. When
 * esmini brings the child down (an uncaught C++ exception aborts it, a bad pointer faults), this process is still
 * there to say so through the protocol, with the scenario, esmini's own words and the simulated time it had
 * reached, and to end the session cleanly: the editor gets an `important` output and `terminated`, and its
 * pending requests an answer.
 */

/** The argument that makes dist/debugAdapter.js the session itself, in the supervisor's child. */
export const SESSION_ARGUMENT = '--modular2simple-session';
/** The child's file descriptor for its progress lines (one JSON object a line: SessionProgress). */
export const PROGRESS_FD = 3;

interface ProtocolMessage {
  seq?: number;
  type?: string;
  command?: string;
  event?: string;
  request_seq?: number;
  arguments?: { program?: unknown };
}

/** Splits a Debug Adapter Protocol stream (`Content-Length: N\r\n\r\n` and N bytes of JSON) into messages. */
export class ProtocolReader {
  private buffer = Buffer.alloc(0);

  constructor(private readonly onMessage: (message: ProtocolMessage) => void) {}

  push(chunk: Buffer): void {
    this.buffer = Buffer.concat([this.buffer, chunk]);
    for (;;) {
      const headerEnd = this.buffer.indexOf('\r\n\r\n');
      if (headerEnd < 0) return;
      const length = /Content-Length: *(\d+)/i.exec(this.buffer.subarray(0, headerEnd).toString('ascii'));
      if (!length) {
        // Not the protocol: dropped up to the next header, as the adapter library does.
        this.buffer = this.buffer.subarray(headerEnd + 4);
        continue;
      }
      const start = headerEnd + 4;
      const end = start + Number(length[1]);
      if (this.buffer.length < end) return;
      const body = this.buffer.subarray(start, end).toString('utf8');
      this.buffer = this.buffer.subarray(end);
      try {
        this.onMessage(JSON.parse(body) as ProtocolMessage);
      } catch {
        // A message that is not JSON is the other side's problem; it is passed on unchanged all the same.
      }
    }
  }
}

function frame(message: object): Buffer {
  const body = Buffer.from(JSON.stringify(message), 'utf8');
  return Buffer.concat([Buffer.from(`Content-Length: ${body.length}\r\n\r\n`, 'ascii'), body]);
}

/** esmini's own words from the child's stderr: an uncaught exception's `what()`, without esmini's empty time and level. */
export function esminiReason(stderr: string): string | undefined {
  const what = /what\(\):\s*(.+)/.exec(stderr);
  if (what) return what[1].replace(/^\[[^\]]*\]\s*\[error\]\s*/, '').trim();
  const assertion = /Assertion [`'].+' failed\.?/.exec(stderr);
  return assertion?.[0];
}

/**
 * The sentence the editor shows when the session's process ended by itself. `reached`: the simulated time its
 * progress page says it reached (progressPage.ts), exact even in a step that reported nothing; else the last progress line's.
 */
export function crashMessage(
  program: string | undefined,
  ended: { code: number | null; signal: NodeJS.Signals | null },
  progress: SessionProgress | undefined,
  reason: string | undefined,
  reached?: number,
): string {
  const how = ended.signal ? `was killed by ${ended.signal}` : `exited with code ${ended.code}`;
  const time = reached ?? progress?.time;
  const last =
    progress === undefined
      ? ''
      : ` (the last it reported: ${progress.what}${reached !== undefined && shownFixed(progress.time) !== shownFixed(reached) ? ` at ${shownFixed(progress.time)} s` : ''})`;
  const when = time === undefined ? 'before its first simulation step' : `at ${shownFixed(time)} s of simulated time${last}`;
  return (
    `The debug session of ${program ? path.basename(program) : 'the scenario'} ended: esmini's process ${how} ${when}.` +
    `${reason ? ` esmini: ${reason}.` : ''} The editor is unaffected; the Debug Console keeps the run's last lines.`
  );
}

/** Runs the session in a child and passes the protocol through; this process exits when the session has ended. */
export function superviseSession(script: string): void {
  // The child's temporary files (esmini's run folder) in a folder of this process's own: gone even when the child is not.
  const temporary = fs.mkdtempSync(path.join(os.tmpdir(), 'modular2simple-debug-'));
  // The page the child stores its step count in at every step, read here when it died (progressPage.ts).
  const progressPage = path.join(temporary, 'progress-page');
  makeProgressPage(progressPage);
  const countPause = pauseCounter(progressPage);
  const child: ChildProcess = spawn(process.execPath, [script, SESSION_ARGUMENT], {
    env: { ...process.env, TMPDIR: temporary, TMP: temporary, TEMP: temporary, [PROGRESS_PAGE_ENV]: progressPage },
    stdio: ['pipe', 'pipe', 'pipe', 'pipe'],
  });
  let program: string | undefined;
  let progress: SessionProgress | undefined;
  let stderrTail = '';
  let ending = false;
  let terminatedSent = false;
  let crashed = false;
  let seq = 1_000_000;
  const pending = new Map<number, string>();

  const send = (message: object) => process.stdout.write(frame({ seq: ++seq, ...message }));
  const answer = (requestSeq: number, command: string, message?: string) =>
    send({ type: 'response', request_seq: requestSeq, command, success: message === undefined, ...(message ? { message } : {}) });

  const fromClient = new ProtocolReader((message) => {
    if (message.type !== 'request' || message.seq === undefined || !message.command) return;
    if (message.command === 'launch' && typeof message.arguments?.program === 'string') program = message.arguments.program;
    if (message.command === 'disconnect' || message.command === 'terminate') ending = true;
    // Counted before the request goes on: the session, busy stepping, sees it after its current step (progressPage.ts).
    if (message.command === 'pause' && !crashed) countPause();
    if (crashed) {
      answer(message.seq, message.command, message.command === 'disconnect' ? undefined : 'the debug session has ended: esmini crashed');
      if (message.command === 'disconnect') setImmediate(finish);
      return;
    }
    pending.set(message.seq, message.command);
  });
  const fromChild = new ProtocolReader((message) => {
    if (message.type === 'response' && message.request_seq !== undefined) pending.delete(message.request_seq);
    if (message.type === 'event' && message.event === 'terminated') terminatedSent = true;
  });

  process.stdin.on('data', (chunk: Buffer) => {
    fromClient.push(chunk);
    if (!crashed) child.stdin?.write(chunk);
  });
  process.stdin.on('end', () => (crashed ? finish() : child.stdin?.end()));
  child.stdout?.on('data', (chunk: Buffer) => {
    fromChild.push(chunk);
    process.stdout.write(chunk);
  });
  child.stderr?.on('data', (chunk: Buffer) => {
    // Passed on (an exception the session logs is loud), and its tail kept for esmini's last words.
    process.stderr.write(chunk);
    stderrTail = (stderrTail + chunk.toString('utf8')).slice(-8192);
  });
  let progressLine = '';
  child.stdio[PROGRESS_FD]?.on('data', (chunk: Buffer) => {
    const lines = (progressLine + chunk.toString('utf8')).split('\n');
    progressLine = lines.pop() ?? '';
    for (const line of lines.reverse()) {
      try {
        progress = JSON.parse(line) as SessionProgress;
        break;
      } catch {
        // A torn line: the one before it stands.
      }
    }
  });
  // The editor stopping this process stops the session with it, through its stdin, as the editor itself would.
  for (const signal of ['SIGTERM', 'SIGINT', 'SIGHUP'] as const)
    process.on(signal, () => {
      ending = true;
      child.stdin?.end();
      setTimeout(() => child.kill('SIGKILL'), 2_000).unref();
    });

  function finish(): void {
    fs.rmSync(temporary, { recursive: true, force: true });
    process.exit(0);
  }

  child.on('close', (code, signal) => {
    if ((code === 0 && !signal) || ending) return finish();
    crashed = true;
    // The session stores its progress in the page when it mapped one, else writes it as lines to PROGRESS_FD.
    const reported = readPageProgress(progressPage) ?? progress;
    const message = crashMessage(program, { code, signal }, reported, esminiReason(stderrTail), readProgressPage(progressPage));
    // `important`: VS Code writes it in the Debug Console and shows it as a notification.
    send({ type: 'event', event: 'output', body: { category: 'important', output: `${message}\n` } });
    for (const [requestSeq, command] of pending) answer(requestSeq, command, message);
    pending.clear();
    if (!terminatedSent) send({ type: 'event', event: 'terminated' });
    // The editor answers terminated with disconnect, which ends this process; one that never does cannot keep it.
    setTimeout(finish, 30_000).unref();
  });
  child.on('error', (error) => {
    process.stderr.write(`modular2simple debug adapter: the session's process did not start: ${error.stack ?? error.message}\n`);
    finish();
  });
}

/** The session's side: progress lines to the supervisor, synchronous so that the last one is written before a crash. */
export function progressWriter(): ((progress: SessionProgress) => void) | undefined {
  try {
    fs.fstatSync(PROGRESS_FD);
  } catch {
    return undefined;
  }
  return (value) => {
    try {
      fs.writeSync(PROGRESS_FD, `${JSON.stringify(value)}\n`);
    } catch {
      // The supervisor gone: nobody left to tell.
    }
  };
}
