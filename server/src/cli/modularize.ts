import * as fs from 'node:fs';
import * as path from 'node:path';
import { writeFilesAtomic } from '../../../common/src/atomic';
import { modularize, ModularizeInput, ModularizeResult, notAPlainScenario } from '../core/modularize';
import { countEditorLines } from '../core/text';
import { parseXml, XmlDocument } from '../core/xml';
import { CliCommand, CliOutput, ExitCode, InputError, parseCommandLine, UnavailableError, UsageError } from './common';

export const MODULARIZE_HELP = `Modularize a library (modular2simple modularize INPUT... --out-dir DIR):
  Finds the ManeuverGroups that recur across the input scenarios (files, or folders searched for
  .xosc files) with the same structure, extracts each once into DIR/simple/NAME.xosc, named after what
  it does, and writes for each input IN/rel.xosc a main DIR/rel.xosc that imports them. Each main is
  flattened and compared with its input (SPEC 8) before anything is written. Catalogs, parameter
  distributions and modular mains among the inputs are left alone.
  --out-dir DIR             the folder to write the mains and simple scenarios to (-o DIR, the older form, too)
  --force                   write into a DIR that exists (never over an input)
  --dry-run                 print what would be made; write nothing
  --format text|json        the report's format
  -q, --quiet               print errors only
  Exit codes: 0 done (or nothing to extract), 1 an input cannot be read or parsed, DIR exists, or a
  main would not flatten back (nothing written), 2 usage, 3 the output could not be written, 4 internal error.`;

const OPTIONS = {
  'out-dir': { type: 'string' },
  // The older name of --out-dir.
  output: { type: 'string', short: 'o' },
  force: { type: 'boolean' },
  'dry-run': { type: 'boolean' },
  format: { type: 'string' },
  quiet: { type: 'boolean', short: 'q' },
} as const;

interface ModularizeArguments {
  inputs: string[];
  out: string;
  force: boolean;
  dryRun: boolean;
  format: 'text' | 'json';
  quiet: boolean;
}

function parseModularizeArguments(args: string[]): ModularizeArguments {
  const { values, positionals } = parseCommandLine(args, OPTIONS);
  if (positionals.length === 0) throw new UsageError('modularize needs input scenarios or folders');
  if (values.output !== undefined && values['out-dir'] !== undefined) throw new UsageError('use either -o or --out-dir');
  const out = values['out-dir'] ?? values.output;
  if (out === undefined || out === '')
    throw new UsageError('modularize needs --out-dir DIR (or -o DIR), the folder to write the mains and simple scenarios to');
  const format = values.format ?? 'text';
  if (format !== 'text' && format !== 'json') throw new UsageError(`--format takes text or json, not '${format}'`);
  return {
    inputs: positionals,
    out: path.resolve(out),
    force: values.force === true,
    dryRun: values['dry-run'] === true,
    format,
    quiet: values.quiet === true,
  };
}

/** Every .xosc file an input names: the file itself, or those below a folder (hidden folders skipped), sorted. */
function scenarioFiles(input: string): string[] {
  const resolved = path.resolve(input);
  if (!fs.existsSync(resolved)) throw new InputError(`${input}: no such file or folder`);
  if (!fs.statSync(resolved).isDirectory()) return [resolved];
  const found: string[] = [];
  const visit = (folder: string) => {
    for (const entry of fs.readdirSync(folder, { withFileTypes: true }).sort((a, b) => a.name.localeCompare(b.name))) {
      if (entry.name.startsWith('.')) continue;
      const full = path.join(folder, entry.name);
      if (entry.isDirectory()) visit(full);
      else if (entry.isFile() && entry.name.toLowerCase().endsWith('.xosc')) found.push(full);
    }
  };
  visit(resolved);
  return found;
}

/** The deepest folder that holds every path. */
function commonFolder(folders: string[]): string {
  let common = folders[0];
  for (const folder of folders.slice(1)) {
    while (common !== folder && !folder.startsWith(common.endsWith(path.sep) ? common : common + path.sep)) common = path.dirname(common);
  }
  return common;
}

function shown(file: string): string {
  const relative = path.relative(process.cwd(), file);
  return relative && !relative.startsWith('..') ? relative : file;
}

function readUtf8(file: string): string {
  try {
    return new TextDecoder('utf-8', { fatal: true }).decode(fs.readFileSync(file));
  } catch (error) {
    if (error instanceof TypeError) throw new InputError(`${shown(file)}: not UTF-8 text; nothing was written`);
    throw new InputError(`${shown(file)}: cannot be read (${(error as Error).message}); nothing was written`);
  }
}

/** Writes every file or none: into a new folder beside OUT renamed into place, or (with --force into an OUT that exists) each atomically. */
async function writeAll(out: string, files: Map<string, string>): Promise<void> {
  if (fs.existsSync(out)) {
    for (const file of files.keys()) fs.mkdirSync(path.dirname(file), { recursive: true });
    const result = await writeFilesAtomic([...files].map(([target, data]) => ({ target, data })));
    if (result.failed)
      throw Object.assign(
        new Error(
          `${shown(result.failed.target)}: ${result.failed.error.message}; ${result.written.length === 0 ? 'nothing was changed' : `only ${result.written.length} files were written`}`,
        ),
        { written: result.written.length },
      );
    return;
  }
  const temporary = path.join(path.dirname(out), `.${path.basename(out)}.modularize-${process.pid}-${Date.now()}`);
  try {
    for (const [file, text] of files) {
      const target = path.join(temporary, path.relative(out, file));
      fs.mkdirSync(path.dirname(target), { recursive: true });
      fs.writeFileSync(target, text);
    }
    fs.renameSync(temporary, out);
  } catch (error) {
    fs.rmSync(temporary, { recursive: true, force: true });
    throw error;
  }
}

function report(
  result: ModularizeResult,
  out: string,
  simpleFolder: string,
  written: boolean,
  io: CliOutput,
  format: 'text' | 'json',
): void {
  const simpleLines = result.behaviours.map((behaviour) => countEditorLines(behaviour.text));
  if (format === 'json') {
    io.out(
      JSON.stringify(
        {
          out,
          written,
          simpleScenarios: result.behaviours.map((behaviour, index) => ({
            file: behaviour.file,
            group: behaviour.groupName,
            lines: simpleLines[index],
            parameterAttributes: behaviour.parameters,
            uses: behaviour.uses.map((use) => ({
              input: result.mains[use.occurrence.input].input,
              main: result.mains[use.occurrence.input].output,
              group: use.occurrence.group.name,
              overrides: use.overrides,
            })),
          })),
          files: result.mains.map((main) => ({
            input: main.input,
            main: main.output,
            linesBefore: main.linesBefore,
            linesAfter: main.linesAfter,
            imports: main.imports.length,
          })),
          keptInline: result.keptInline,
          totals: result.totals,
        },
        null,
        2,
      ),
    );
    return;
  }
  if (result.behaviours.length === 0 && result.keptInline.length > 0) {
    const groups = result.keptInline.length;
    io.out(
      `${groups} recurring group${groups === 1 ? '' : 's'} left inline, each for the reason below: nothing extracted, nothing written`,
    );
  } else if (result.behaviours.length === 0) {
    io.out(
      `no ManeuverGroup recurs across the ${result.mains.length} scenario${result.mains.length === 1 ? '' : 's'}: nothing extracted, nothing written`,
    );
  } else {
    const files = new Set(result.behaviours.map((behaviour) => behaviour.file)).size;
    const shared = files < result.behaviours.length ? ` holding ${result.behaviours.length} behaviours` : '';
    io.out(`${files} simple scenario${files === 1 ? '' : 's'}${shared} in ${shown(simpleFolder)}:`);
    result.behaviours.forEach((behaviour, index) => {
      const mains = [...new Set(behaviour.uses.map((use) => shown(result.mains[use.occurrence.input].output)))];
      io.out(
        `  ${path.basename(behaviour.file)} (group ${behaviour.groupName}, ${simpleLines[index]} lines): ${behaviour.uses.length} uses in ${mains.length} file${mains.length === 1 ? '' : 's'}`,
      );
      io.out(`    overridable: ${behaviour.parameters.length > 0 ? behaviour.parameters.join(', ') : 'nothing (every use is the same)'}`);
      io.out(`    used in: ${mains.join(', ')}`);
    });
  }
  for (const kept of result.keptInline) io.out(`  kept inline: ${kept.group} in ${shown(kept.input)}: ${kept.reason}`);
  const width = Math.max(
    8,
    ...result.mains.map((main) => shown(main.output).length),
    ...result.behaviours.map((behaviour) => shown(behaviour.file).length + 2),
  );
  io.out(`${'file'.padEnd(width)}  ${'before'.padStart(7)}  ${'after'.padStart(7)}  reduction`);
  for (const main of result.mains) {
    const reduction = main.linesBefore === 0 ? 0 : (1 - main.linesAfter / main.linesBefore) * 100;
    io.out(
      `${shown(main.output).padEnd(width)}  ${String(main.linesBefore).padStart(7)}  ${String(main.linesAfter).padStart(7)}  ${reduction.toFixed(1).padStart(7)} %`,
    );
  }
  // A simple scenario that several behaviours share is counted once.
  result.behaviours.forEach((behaviour, index) => {
    if (result.behaviours.findIndex((other) => other.file === behaviour.file) !== index) return;
    io.out(`${('+ ' + shown(behaviour.file)).padEnd(width)}  ${''.padStart(7)}  ${String(simpleLines[index]).padStart(7)}`);
  });
  const { totals } = result;
  io.out(
    `${'total (SPEC 9)'.padEnd(width)}  ${totals.linesBefore.toLocaleString('en-US').padStart(7)}  ${totals.linesAfter.toLocaleString('en-US').padStart(7)}  ${totals.reduction.toFixed(1).padStart(7)} %`,
  );
}

/** `modular2simple modularize INPUT... -o OUT [--force] [--dry-run] [--format json]`. */
async function modularizeCommand(args: string[], io: CliOutput): Promise<number> {
  const options = parseModularizeArguments(args);
  const { out } = options;
  const files = [...new Set(options.inputs.flatMap(scenarioFiles))];
  if (!options.dryRun && fs.existsSync(out) && !options.force)
    throw new InputError(`${shown(out)} exists; nothing was written (--force writes into it)`);
  if (!fs.existsSync(path.dirname(out)))
    throw new UnavailableError(`${shown(out)}: the folder ${shown(path.dirname(out))} does not exist; nothing was written`);

  const scenarios: string[] = [];
  const texts = new Map<string, { text: string; document: XmlDocument }>();
  let unreadable = 0;
  for (const file of files) {
    const text = readUtf8(file);
    const document = parseXml(text);
    const error = document.problems.find((problem) => problem.severity === 'error');
    if (error) {
      const { line, character } = document.lines.positionAt(error.start);
      io.err(`${shown(file)}:${line + 1}:${character + 1}: error: ${error.message}`);
      unreadable++;
      continue;
    }
    const leftAlone = notAPlainScenario(document);
    if (leftAlone) {
      if (!options.quiet) io.err(`${shown(file)}: left alone: ${leftAlone}`);
      continue;
    }
    scenarios.push(file);
    texts.set(file, { text, document });
  }
  if (unreadable > 0) {
    io.err(`${unreadable} input${unreadable === 1 ? '' : 's'} cannot be parsed; nothing was written`);
    return ExitCode.problems;
  }
  if (scenarios.length === 0) throw new InputError('no scenario among the inputs; nothing was written');

  const base = commonFolder(
    options.inputs.map((input) => {
      const resolved = path.resolve(input);
      return fs.statSync(resolved).isDirectory() ? resolved : path.dirname(resolved);
    }),
  );
  const relative = scenarios.map((file) => path.relative(base, file));
  let simpleName = 'simple';
  for (let n = 2; relative.some((rel) => rel.split(path.sep)[0].toLowerCase() === simpleName.toLowerCase()); n++)
    simpleName = `simple_${n}`;
  const simpleFolder = path.join(out, simpleName);
  const inputs: ModularizeInput[] = scenarios.map((file, index) => ({
    path: file,
    output: path.join(out, relative[index]),
    ...(texts.get(file) as { text: string; document: XmlDocument }),
  }));
  // An output that exists is compared with the inputs by identity (links too), each file looked at once.
  const identity = (file: string) => {
    const stat = fs.statSync(file);
    return `${stat.dev}:${stat.ino}`;
  };
  const inputIdentities = fs.existsSync(out) ? new Set(files.map(identity)) : new Set<string>();
  for (const input of inputs) {
    if (fs.existsSync(input.output) && inputIdentities.has(identity(input.output)))
      throw new InputError(`refusing to write ${shown(input.output)}: it is an input; choose another OUT`);
  }

  const result = await modularize(inputs, { simpleFolder });
  if (result.failures.length > 0) {
    for (const failure of result.failures)
      io.err(`${shown(failure.input)}: error: its main would not flatten back to an equivalent scenario: ${failure.difference}`);
    io.err(
      `${result.failures.length} main${result.failures.length === 1 ? '' : 's'} would differ from ${result.failures.length === 1 ? 'its input' : 'their inputs'}; nothing was written`,
    );
    return ExitCode.problems;
  }
  const nothing = result.behaviours.length === 0;
  const outputs = new Map<string, string>();
  if (!nothing) {
    for (const behaviour of result.behaviours) outputs.set(behaviour.file, behaviour.text);
    for (const main of result.mains) outputs.set(main.output, main.text);
  }
  let written = false;
  if (!options.dryRun && !nothing) {
    try {
      await writeAll(out, outputs);
      written = true;
    } catch (error) {
      io.err(`${shown(out)}: error: cannot write the output (${(error as Error).message})`);
      return ExitCode.io;
    }
  }
  if (!options.quiet || options.format === 'json') report(result, out, simpleFolder, written, io, options.format);
  if (!options.quiet && options.format === 'text') {
    if (written) io.err(`wrote ${outputs.size} files to ${shown(out)}`);
    else if (options.dryRun && !nothing) io.err(`--dry-run: nothing was written`);
  }
  return ExitCode.ok;
}

export const MODULARIZE: CliCommand = { help: MODULARIZE_HELP, run: modularizeCommand };
