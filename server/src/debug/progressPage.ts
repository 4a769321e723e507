import * as fs from 'node:fs';
import * as os from 'node:os';

/*
 * A page of memory shared by a debug session's process and its supervisor (supervisor.ts), written by one side and read
 * by the other without a system call on the reader's side.
 *
 * The simulated time a debug session has reached, kept where its supervisor can read it after the session's process
 * died in the middle of a step. The session writes the number of steps esmini has made into a page of
 * memory at every step: a file the supervisor made, mapped shared (libc's mmap through koffi, as esmini's library is
 * called), so a write is a store to memory, not a system call; after the child dies, the supervisor reads the file,
 * whose pages hold what the child last stored. A step costs esmini microseconds; a progress line written at every
 * step (a system call) would cost about as much as the step.
 *
 * The session's progress (the last storyboard transition or condition it reported, and its time) goes there too, at
 * each of esmini's callbacks: a store, where a line to the supervisor's pipe was a system call and woke the supervisor.
 *
 * The other way, the pause requests: the supervisor reads the editor's requests before the session does, and counts
 * each pause into the page (a write to the file, which the session's shared mapping sees); the session, stepping esmini
 * without returning to its event loop for milliseconds at a time, reads the count after every step and stops at once.
 */

/** What the session last reported reaching: written synchronously, so that it outlives a crash in the very next call. */
export interface SessionProgress {
  /** Simulated seconds. */
  time: number;
  /** What happened then: `Act ClearanceAct running`, `stepping`. */
  what: string;
}

/** The environment variable naming the page's file, set by the supervisor for its child. */
export const PROGRESS_PAGE_ENV = 'MODULAR2SIMPLE_PROGRESS_PAGE';
/** The page's size, bytes: the file the supervisor makes and the child maps. */
export const PROGRESS_PAGE_BYTES = 4096;

/**
 * The page's slots (Float64): the steps made in the run, its time step, a mark that they were written (the session's),
 * the pause requests (the supervisor's), the progress's time and the length of its text (the session's); the text's
 * UTF-8 bytes from PROGRESS_TEXT on.
 */
const STEPS = 0;
const TIME_STEP = 1;
const WRITTEN = 2;
const PAUSES = 3;
const PROGRESS_TIME = 4;
const PROGRESS_LENGTH = 5;
const PROGRESS_TEXT = 64;
/** Written into WRITTEN once the session set the time step: a page of zeros says nothing. */
const MARK = 29.5;

/** What the session writes: the run's time step once, then the steps esmini has made after each. */
export interface StepCounter {
  start(timeStep: number): void;
  steps(count: number): void;
}

/** The session's side of the page: its step counter, its progress, and the pause requests its supervisor has counted so far. */
export interface SessionPage extends StepCounter {
  pauseRequests(): number;
  progress(value: SessionProgress): void;
}

type KoffiModule = typeof import('koffi');

/** Maps the page the supervisor made (its file in PROGRESS_PAGE_ENV); undefined where there is none or it cannot be mapped. */
export function mapProgressPage(file = process.env[PROGRESS_PAGE_ENV]): SessionPage | undefined {
  if (!file || process.platform === 'win32') return undefined;
  // Required here: koffi is a native module, loaded only by the processes that run a scenario.
  const koffi = require('koffi') as KoffiModule;
  const libc = koffi.load(process.platform === 'darwin' ? 'libSystem.dylib' : 'libc.so.6');
  const mmap = libc.func('void *mmap(void *addr, size_t length, int prot, int flags, int fd, long offset)');
  const fd = fs.openSync(file, 'r+');
  let pointer: unknown;
  try {
    // PROT_READ | PROT_WRITE, MAP_SHARED (the same values on Linux and macOS); the mapping outlives the descriptor.
    pointer = mmap(null, PROGRESS_PAGE_BYTES, 1 | 2, 1, fd, 0);
  } finally {
    fs.closeSync(fd);
  }
  // MAP_FAILED is (void *)-1.
  if (!pointer || koffi.address(pointer) === BigInt.asUintN(64, -1n)) return undefined;
  const memory = koffi.view(pointer, PROGRESS_PAGE_BYTES);
  const page = new Float64Array(memory);
  const text = new Uint8Array(memory, PROGRESS_TEXT);
  const encoder = new TextEncoder();
  return {
    start(timeStep) {
      page[STEPS] = 0;
      page[TIME_STEP] = timeStep;
      page[WRITTEN] = MARK;
    },
    steps(count) {
      page[STEPS] = count;
    },
    pauseRequests() {
      return page[PAUSES];
    },
    progress({ time, what }) {
      // The text first, its length last: a length always measures text written (a longer text is cut at a character).
      const { written } = encoder.encodeInto(what, text);
      page[PROGRESS_TIME] = time;
      page[PROGRESS_LENGTH] = written;
    },
  };
}

// The child stores through a Float64Array, in the machine's byte order, which the supervisor reads and writes slots in too.
const BYTE_ORDER = os.endianness();
const slotIn = (bytes: Buffer, index: number): number => bytes[`readDouble${BYTE_ORDER}`](index * 8);
const writeSlot = (bytes: Buffer, value: number): number => bytes[`writeDouble${BYTE_ORDER}`](value);

/** The supervisor's side: a zeroed page file for the child to map. */
export function makeProgressPage(file: string): void {
  fs.writeFileSync(file, Buffer.alloc(PROGRESS_PAGE_BYTES));
}

/** The supervisor's side: counts a pause request into the page (the file's slot, seen by the session's mapping). */
export function pauseCounter(file: string): () => void {
  let count = 0;
  const slot = Buffer.alloc(8);
  return () => {
    count++;
    writeSlot(slot, count);
    const fd = fs.openSync(file, 'r+');
    try {
      fs.writeSync(fd, slot, 0, 8, PAUSES * 8);
    } finally {
      fs.closeSync(fd);
    }
  };
}

/** The page file's bytes, as the session left them; undefined when there is none. */
function pageBytes(file: string): Buffer | undefined {
  try {
    return fs.readFileSync(file);
  } catch {
    return undefined;
  }
}

/** The progress the session last stored in the page (SessionPage.progress); undefined when it stored none. */
export function readPageProgress(file: string): SessionProgress | undefined {
  const bytes = pageBytes(file);
  if (bytes?.length !== PROGRESS_PAGE_BYTES) return undefined;
  const length = slotIn(bytes, PROGRESS_LENGTH);
  if (!(length > 0 && length <= PROGRESS_PAGE_BYTES - PROGRESS_TEXT && Number.isInteger(length))) return undefined;
  return { time: slotIn(bytes, PROGRESS_TIME), what: bytes.toString('utf8', PROGRESS_TEXT, PROGRESS_TEXT + length) };
}

/** The simulated time the page says the session reached (steps × time step: esmini's time after them), s; undefined when never written. */
export function readProgressPage(file: string): number | undefined {
  const bytes = pageBytes(file);
  if (bytes === undefined || bytes.length < 3 * 8) return undefined;
  // Each slot read at its offset: a Float64Array over readFileSync's buffer would need it 8-byte aligned, which Node does not promise.
  const slot = (index: number) => slotIn(bytes, index);
  const [steps, timeStep] = [slot(STEPS), slot(TIME_STEP)];
  if (slot(WRITTEN) !== MARK || !(timeStep > 0) || !(steps >= 0)) return undefined;
  return steps * timeStep;
}
