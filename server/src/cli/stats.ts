import * as fs from 'node:fs';
import * as path from 'node:path';
import { splitScenarioPath } from '../core/sources';
import { libraryStats } from '../core/stats';
import { CliCommand, CliOutput, ExitCode, InputError, UsageError } from './common';
import { parseOptions, READING_OPTIONS_HELP } from './options';

/** The reading options stats takes: all but --schema-version (it counts lines; check checks a schema). */
const STATS_READING_OPTIONS_HELP = READING_OPTIONS_HELP.replace(/\n {2}--schema-version[^\n]*\n[^\n]*/, '');

/** `modular2simple stats LIBRARY [--format json]`: lines of code of a library (the paper's Table 1). */
async function statsCommand(args: string[], io: CliOutput): Promise<number> {
  const options = parseOptions(args);
  if (options.positional.length !== 1) throw new UsageError('stats takes one library folder');
  const library = options.positional[0];
  if (options.format === 'sarif') throw new UsageError('stats writes text or json, not sarif');
  // Lines are counted whatever a schema says; a schema check is check's (flattening here checks none).
  if (args.some((arg) => arg === '--schema-version' || arg.startsWith('--schema-version=')))
    throw new UsageError(
      `stats counts lines and checks no schema, so --schema-version does not apply to it: run 'modular2simple check ${library} --schema-version V' to check the scenarios against a schema`,
    );
  if (!fs.existsSync(library) || !fs.statSync(library).isDirectory()) throw new InputError(`${library}: no such folder`);
  const stats = await libraryStats(library, options.limits, process.cwd(), [
    ...options.scenarioPath,
    ...splitScenarioPath(process.env.SCENARIO_PATH),
  ]);
  for (const problem of stats.problems) io.err(`${library}: error: ${problem}`);
  if (options.format === 'json') {
    io.out(JSON.stringify(stats, null, 2));
  } else {
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
  Exit codes: 0 done, 1 a scenario of the library could not be flattened or the folder is missing, 2 usage,
  4 internal error.`,
  run: statsCommand,
};
