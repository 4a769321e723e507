import { asksForHelp, CliCommand, CliOutput, ExitCode, failure, UsageError, VERSION } from './cli/common';

export { ExitCode } from './cli/common';

/**
 * The commands, each loaded only when it runs (a flatten does not load the packer's ZIP writer nor
 * esmini's runner). A new command is one row here and one file in cli/ exporting its CliCommand: its
 * help (`COMMAND --help`) and what it runs, throwing UsageError, InputError or UnavailableError
 * (cli/common.ts) for exit codes 2, 1 and 3.
 */
const COMMANDS: Record<string, () => Promise<CliCommand>> = {
  flatten: async () => (await import('./cli/flatten')).FLATTEN,
  pack: async () => (await import('./cli/pack')).PACK,
  check: async () => (await import('./cli/check')).CHECK,
  stats: async () => (await import('./cli/stats')).STATS,
  format: async () => (await import('./cli/format')).FORMAT,
  run: async () => (await import('./cli/run')).RUN,
  vary: async () => (await import('./cli/vary')).VARY,
  modularize: async () => (await import('./cli/modularize')).MODULARIZE,
  batch: async () => (await import('./cli/batch')).BATCH,
  worker: async () => (await import('./cli/worker')).WORKER,
  'qc-bundle': async () => (await import('./cli/qcBundle')).QC_BUNDLE,
  export: async () => (await import('./cli/export')).EXPORT,
  library: async () => (await import('./cli/library')).LIBRARY,
  // The original tool's forms.
  '-cxm': async () => (await import('./cli/pack')).CONVERT_XOSC_INTO_MOSC,
  '--convert-xosc-into-mosc': async () => (await import('./cli/pack')).CONVERT_XOSC_INTO_MOSC,
  '-cmx': async () => (await import('./cli/flatten')).CONVERT_MOSC_TO_XOSC,
  '--convert-mosc-to-xosc': async () => (await import('./cli/flatten')).CONVERT_MOSC_TO_XOSC,
};

/** The names the command line takes, in the table's order (aliases included). */
export const COMMAND_NAMES: readonly string[] = Object.keys(COMMANDS);

/** Runs the command line; returns the exit code. Never throws. */
export async function main(argv: string[], io: CliOutput): Promise<number> {
  try {
    if (argv.length === 0 || argv[0] === '-h' || argv[0] === '--help' || argv[0] === 'help') {
      const { HELP } = await import('./cli/help');
      (argv.length === 0 ? io.err : io.out)(HELP);
      return argv.length === 0 ? ExitCode.usage : ExitCode.ok;
    }
    if (argv[0] === '-v' || argv[0] === '--version') {
      io.out(VERSION);
      return ExitCode.ok;
    }
    const [name, ...rest] = argv;
    const load = Object.hasOwn(COMMANDS, name) ? COMMANDS[name] : undefined;
    if (!load) {
      // A wrong option is reported before a wrong command, as the shared options are read first.
      (await import('./cli/options')).parseOptions(rest);
      throw new UsageError(`unknown command '${name}'`);
    }
    const command = await load();
    if (asksForHelp(rest)) {
      io.out(command.help);
      return ExitCode.ok;
    }
    return await command.run(rest, io);
  } catch (error) {
    const failed = failure(error);
    if (failed) {
      io.err(failed.message);
      return failed.code;
    }
    io.err(
      `modular2simple: internal error: ${(error as Error).stack ?? (error as Error).message}\nPlease report this with the input that caused it.`,
    );
    return ExitCode.internal;
  }
}

/** Standard output, set up on first use: a run that writes only files never pays for opening it. */
function standardOutput(): NodeJS.WriteStream {
  if (!stdoutReady) {
    stdoutReady = true;
    // A closed pipe (`| head`) ends the output quietly instead of with a stack trace.
    process.stdout.on('error', (error: NodeJS.ErrnoException) => {
      if (error.code === 'EPIPE') process.exit(process.exitCode ?? 0);
    });
  }
  return process.stdout;
}
let stdoutReady = false;

/** Runs the process's command line and sets its exit code. */
export function runFromCommandLine(): void {
  main(process.argv.slice(2), {
    out: (text) => standardOutput().write(text.endsWith('\n') ? text : text + '\n'),
    err: (text) => process.stderr.write(text + '\n'),
    ownsProcess: true,
  }).then(
    (code) => {
      process.exitCode = code;
    },
    (error: unknown) => {
      // main answers every failure itself; reaching this is a bug, reported with its stack.
      process.stderr.write(`modular2simple: internal error: ${error instanceof Error ? error.stack : String(error)}\n`);
      process.exitCode = ExitCode.io;
    },
  );
}

// Bundled, the program starts in cli/start.ts (dist/cli.js); from source it may start here.
if (require.main === module) runFromCommandLine();
