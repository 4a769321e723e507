import * as fs from 'node:fs';
import * as path from 'node:path';
import { parseArgs, ParseArgsConfig } from 'node:util';
import { isSameFile, writeFilesAtomicSync } from '../../../common/src/atomic';
import { formatProblem, Problem, uniqueProblems } from '../core/problems';
import { displayRef, nodeFileSystem, SourceRef } from '../core/sources';
import { besideOutputWritable } from '../core/flatten/besideOutput';
import type { PackagedFile } from '../core/flatten/types';
import { CRITERIA_FAILED_EXIT } from '../batch/criteria';

export const VERSION = '0.1.0';

/** Exit codes of every command, as documented in docs/cli.md (130: batch interrupted, run it again to finish). */
export const ExitCode = { ok: 0, problems: 1, usage: 2, io: 3, internal: 4, criteria: CRITERIA_FAILED_EXIT, interrupted: 130 } as const;

/** Where a command prints: its result on `out`, problems and summaries on `err`. */
export interface CliOutput {
  out: (text: string) => void;
  err: (text: string) => void;
  /** Set when the command runs as the program itself (dist/cli.js), not called inside another process: it may then tune process-wide V8 settings. */
  ownsProcess?: boolean;
}

/** Wrong usage: printed with a pointer to --help, exit 2. */
export class UsageError extends Error {}

/** An input that cannot be used: printed as an error, exit 1. */
export class InputError extends Error {}

/** What a command needs beside its inputs cannot be had (no esmini, Redis unreachable, a results folder not writable): printed as an error, exit 3. */
export class UnavailableError extends Error {}

/** How main (cli.ts) answers each error class: a message on standard error and an exit code. */
export function failure(error: unknown): { message: string; code: number } | undefined {
  if (error instanceof UsageError)
    return { message: `modular2simple: ${error.message}\nRun 'modular2simple --help' for usage.`, code: ExitCode.usage };
  if (error instanceof InputError) return { message: `modular2simple: error: ${error.message}`, code: ExitCode.problems };
  if (error instanceof UnavailableError) return { message: `modular2simple: error: ${error.message}`, code: ExitCode.io };
  return undefined;
}

/** What a command runs: its arguments after the command name, its exit code. */
export type Command = (args: string[], io: CliOutput) => Promise<number>;

/** A command of the table in cli.ts: its help (printed for `--help` or `-h`, exit 0) and what it runs. */
export interface CliCommand {
  help: string;
  run: Command;
}

/** An option's whole number (a count, an index, a seed); undefined when the option is absent. */
export function wholeNumber(text: string | undefined, option: string): bigint | undefined {
  if (text === undefined) return undefined;
  if (!/^\d+$/.test(text.trim())) throw new UsageError(`${option} takes a whole number, not '${text}'`);
  return BigInt(text.trim());
}

/**
 * --index I of the distribution `file` (as the user typed it), which has `count` concrete scenarios: a usage error
 * naming the option, the file and the range it takes when I lies outside, as every other wrong option value is.
 */
export function checkIndexInRange(index: bigint, count: bigint, file: string): void {
  if (index < count) return;
  if (count === 0n) throw new UsageError(`--index ${index} is out of range: ${file} has no concrete scenario`);
  const scenarios = count === 1n ? '1 concrete scenario, numbered 0' : `${count} concrete scenarios, numbered 0..${count - 1n}`;
  throw new UsageError(`--index ${index} is out of range: ${file} has ${scenarios}; give --index one of those`);
}

/** --duration's seconds: undefined when not given (each scenario's own end), a UsageError when not a positive number. */
export function durationOption(text: string | undefined): number | undefined {
  if (text === undefined) return undefined;
  const duration = Number(text);
  if (!(duration > 0) || !Number.isFinite(duration) || text.trim() === '')
    throw new UsageError(`--duration takes a positive number of seconds, not '${text}'`);
  return duration;
}

/** Whether the arguments ask for the command's help: `--help` or `-h` before any `--`. */
export function asksForHelp(args: readonly string[]): boolean {
  const end = args.indexOf('--');
  return (end < 0 ? args : args.slice(0, end)).some((arg) => arg === '--help' || arg === '-h');
}

/** An option followed by a value that begins with '-' (--duration -5, -o -x.xosc): which value, and how to give it. */
export function dashValueMessage(flag: string, longFlag: string, value: string): string {
  return `${flag} is followed by '${value}', which begins with '-' as an option does: if it is ${flag}'s value, write ${longFlag}=${value}; else give ${flag} its value`;
}

/**
 * The arguments read by node:util's parseArgs (strict, positionals allowed); a wrong one is a UsageError
 * worded as the shared options word it (`unknown option '--x'`, `--name needs a value`).
 */
export function parseCommandLine<const T extends NonNullable<ParseArgsConfig['options']>>(
  args: string[],
  options: T,
): ReturnType<typeof parseArgs<{ args: string[]; options: T; strict: true; allowPositionals: true }>> {
  try {
    return parseArgs({ args, options, strict: true as const, allowPositionals: true as const });
  } catch (error) {
    const message = (error as Error).message;
    const unknown = /Unknown option '([^']+)'/.exec(message);
    const missing = /Option '(?:-\w, )?(--[\w-]+)/.exec(message);
    const ambiguous = /Option '([^']+)' argument is ambiguous[\s\S]*use '(--[\w-]+)=-XYZ'/.exec(message);
    if (ambiguous) {
      // A value that begins with '-' (--duration -5, --index -1): node's first line alone says neither which value nor how to give it.
      throw new UsageError(dashValueMessage(ambiguous[1], ambiguous[2], args[args.indexOf(ambiguous[1]) + 1] ?? ''));
    }
    throw new UsageError(
      unknown
        ? `unknown option '${unknown[1]}'`
        : missing && /argument missing/.test(message)
          ? `${missing[1]} needs a value`
          : message.split('\n')[0],
    );
  }
}

export function checkInputExists(input: string): void {
  if (!fs.existsSync(input)) throw new InputError(`${input}: no such file or folder`);
  const resolved = path.resolve(input);
  if (fs.statSync(resolved).isDirectory() && !fs.existsSync(path.join(resolved, 'main.xosc'))) {
    throw new InputError(`${input}: the folder holds no main.xosc, so it is not an unpacked package`);
  }
}

/** Whether a command's text prints a problem: errors always, warnings and information unless quiet, hints (an unused parameter) never: they are for the editor, where they show faded. */
export function printed(problem: Problem, quiet: boolean): boolean {
  return problem.severity === 'error' || (!quiet && problem.severity !== 'hint');
}

/** Prints the problems (hints never, warnings unless quiet) and counts errors and warnings. */
export function report(problems: Problem[], io: CliOutput, quiet: boolean): { errors: number; warnings: number } {
  let errors = 0;
  let warnings = 0;
  for (const problem of uniqueProblems(problems)) {
    if (problem.severity === 'error') errors++;
    else if (problem.severity === 'warning') warnings++;
    if (printed(problem, quiet)) io.err(formatProblem(problem, process.cwd()));
  }
  return { errors, warnings };
}

/** Refuses to write over any file the run read. */
export function checkNotAnInput(output: string, inputs: SourceRef[]): void {
  for (const input of inputs) {
    if (fs.existsSync(output) && isSameFile(output, input.disk)) {
      throw new InputError(`refusing to write ${output}: it is an input (${displayRef(input, process.cwd())}); choose another output file`);
    }
  }
}

/** Writes every output or none; `-` is standard output. */
/** The package files a flattening returns that may be written where `at` puts them (besideOutputWritable), its warnings printed after `label`. */
export async function writablePackagedFiles<File extends PackagedFile>(
  files: readonly File[],
  label: string,
  io: CliOutput,
  quiet: boolean,
  at?: (file: File) => string,
): Promise<File[]> {
  const { files: writable, warnings } = await besideOutputWritable(files, nodeFileSystem, at);
  if (!quiet) for (const warning of warnings) io.err(`${label}: warning: ${warning}`);
  return writable;
}

export async function write(
  outputs: { target: string; data: string | Uint8Array; summary: string }[],
  io: CliOutput,
  quiet: boolean,
): Promise<number> {
  const files = outputs.filter((output) => output.target !== '-');
  for (const output of files) {
    const directory = path.dirname(path.resolve(output.target));
    if (!fs.existsSync(directory)) {
      io.err(`${output.target}: error: cannot write the output (the folder ${directory} does not exist); nothing was changed`);
      return ExitCode.io;
    }
  }
  // Blocking writes: the data is in memory, and a thread-pool turn per call was a noticeable part of a short run.
  const result = writeFilesAtomicSync(files.map((output) => ({ target: output.target, data: output.data })));
  if (result.failed) {
    const { target, error } = result.failed;
    const changed =
      result.written.length === 0
        ? 'nothing was changed'
        : `only ${result.written.join(', ')} ${result.written.length === 1 ? 'was' : 'were'} written`;
    io.err(`${target}: error: cannot write the output (${error.message}); ${changed}`);
    return ExitCode.io;
  }
  for (const output of outputs) {
    if (output.target === '-') io.out(output.data as string);
    else if (!quiet) io.err(output.summary);
  }
  return ExitCode.ok;
}
