import * as fs from 'node:fs';
import * as path from 'node:path';
import { splitScenarioPath } from '../core/sources';
import { libraryStats } from '../core/stats';
import { libraryFolders } from '../libraries';
import { CliCommand, CliOutput, ExitCode, InputError, UsageError } from './common';
import { optionTokens, parseOptions, READING_OPTIONS_HELP } from './options';

/** The reading options stats takes: all but --schema-version (it counts lines; check checks a schema); its own --root default. */
const STATS_READING_OPTIONS_HELP = READING_OPTIONS_HELP.replace(/\n {2}--schema-version[^\n]*\n[^\n]*/, '').replace(
  /\n {2}--root DIR[^\n]*\n[^\n]*/,
  `
  --root DIR                where the search upward from a main's folder for the simple scenarios it
                            names stops (default: the library folder; check's default is the working directory)`,
);

/** The shared options that mean nothing to stats, and what to do instead ('LIB' stands for the library given). */
const REFUSED: Readonly<Record<string, string>> = {
  'schema-version':
    "stats counts lines and checks no schema, so --schema-version does not apply to it: run 'modular2simple check LIB --schema-version V' to check the scenarios against a schema",
  simulator:
    "stats counts lines, the same whatever simulator runs them, so --simulator does not apply to it: run 'modular2simple check LIB --simulator S' to see what a simulator refuses or runs otherwise",
  carla:
    "stats counts lines, the same whatever simulator runs them, so --carla does not apply to it: run 'modular2simple check LIB --simulator carla --carla R' for a ScenarioRunner release",
  output: "stats writes no file, so -o/--output does not apply to it: redirect its standard output ('> table.txt')",
  'out-dir': "stats writes no file, so --out-dir does not apply to it: redirect its standard output ('> table.txt')",
  force: 'stats writes nothing, so --force does not apply to it: a scenario that cannot be flattened is reported and left out of the table',
  'self-contained': "--self-contained is pack's: stats writes no package",
  'include-scenario-path': "--include-scenario-path is pack's: stats writes no package",
};

/** `modular2simple stats LIBRARY [--format json]`: lines of code of a library (the paper's Table 1). */
async function statsCommand(args: string[], io: CliOutput): Promise<number> {
  const options = parseOptions(args);
  if (options.positional.length !== 1) throw new UsageError('stats takes one library folder');
  const library = options.positional[0];
  if (options.format === 'sarif') throw new UsageError('stats writes text or json, not sarif');
  for (const token of optionTokens(args)) {
    const refusal = token.kind === 'option' ? REFUSED[token.name] : undefined;
    if (refusal) throw new UsageError(refusal.replace('LIB', library));
  }
  if (options.root !== undefined && !(fs.existsSync(options.root) && fs.statSync(options.root).isDirectory()))
    throw new InputError(`--root ${options.root}: no such folder`);
  if (!fs.existsSync(library) || !fs.statSync(library).isDirectory()) throw new InputError(`${library}: no such folder`);
  const stats = await libraryStats(
    library,
    options.limits,
    process.cwd(),
    [...options.scenarioPath, ...splitScenarioPath(process.env.SCENARIO_PATH)],
    libraryFolders([]),
    options.root,
  );
  for (const problem of stats.problems) io.err(`${library}: error: ${problem}`);
  if (options.format === 'json') {
    io.out(JSON.stringify(stats, null, 2));
  } else if (stats.rows.length > 0) {
    // With no scenario the error says why: a table of zeros beside it would read as a count.
    const sharedNames = stats.shared.map((item) => `+ ${path.relative(path.resolve(library), item.file)}`);
    const width = Math.max(8, ...stats.rows.map((row) => row.scenario.length), ...sharedNames.map((name) => name.length));
    io.out(`${'#'.padStart(3)}  ${'scenario'.padEnd(width)}  ${'modular'.padStart(8)}  ${'flattened'.padStart(9)}  reduction`);
    stats.rows.forEach((row, index) => {
      io.out(
        `${String(index + 1).padStart(3)}  ${row.scenario.padEnd(width)}  ${String(row.modularLines).padStart(8)}  ${String(row.flattenedLines).padStart(9)}  ${row.reduction.toFixed(1).padStart(8)} %`,
      );
    });
    stats.shared.forEach((item, index) => io.out(`     ${sharedNames[index].padEnd(width)}  ${String(item.lines).padStart(8)}`));
    const { totals } = stats;
    io.out(
      `     ${'total'.padEnd(width)}  ${totals.modularLines.toLocaleString('en-US').padStart(8)}  ${totals.flattenedLines.toLocaleString('en-US').padStart(9)}  ${totals.reduction.toFixed(1).padStart(8)} %`,
    );
  }
  return stats.problems.length > 0 ? ExitCode.problems : ExitCode.ok;
}

export const STATS: CliCommand = {
  help: `Lines of code of a library, modular and flattened (the paper's Table 1) (modular2simple stats LIBRARY [--format text|json]):
  --format text|json        a table (the default) or JSON, on standard output
${STATS_READING_OPTIONS_HELP}
  Exit codes: 0 done, 1 a scenario of the library could not be flattened, the folder is missing or it holds
  nothing modular, 2 usage, 4 internal error.`,
  run: statsCommand,
};
