import * as path from 'node:path';
import { findModule, LibraryListing, LibraryModule, listLibraries } from '../core/library';
import { LIBRARY_PREFIX } from '../core/sources';
import { libraryFolders, listTemplates, templateOutputs } from '../libraries';
import { closestMatch } from '../core/text';
import { CliCommand, CliOutput, ExitCode, InputError, parseCommandLine, UsageError, write } from './common';
import { cliFileSystem } from './fileSystem';

export const LIBRARY_HELP = `The scenario library: modules a main file names as scenarioFileName="library:NAME"
(modular2simple library list|show NAME|path|templates|new TEMPLATE -o FILE.xosc [--library DIR]... [--format text|json]):
  list                      every module: its name, file, example main and what it does
  show NAME                 one module: what it does, its actor, its keys with units, ranges and
                            defaults, its example main and picture ("did you mean" for a misspelt NAME)
  path                      the library folders, in the order they are searched, one per line (the
                            first holding a name wins): the folders to add to SCENARIO_PATH, say
  templates                 the scenario templates (mains composed from library modules for common
                            test protocols): name, title and what each does
  new TEMPLATE -o FILE.xosc a new scenario from a template: FILE.xosc, the template's road beside it
                            and, for a template with a distribution, FILE.distribution.xosc naming it;
                            an existing file is never replaced (nothing is written)
  --library DIR             a library folder of your own, searched before SCENARIO_LIBRARY_PATH's
                            folders and the built-in library (may be given more than once)
  --format text|json        text (the default) or JSON, on standard output
  Exit codes: 0 done, 1 a library folder or module could not be read (each named; the rest is listed)
  or NAME is no module, 2 usage, 4 internal error.`;

const OPTIONS = {
  library: { type: 'string', multiple: true },
  format: { type: 'string' },
  output: { type: 'string', short: 'o' },
  quiet: { type: 'boolean', short: 'q' },
} as const;

/** `library templates` and `library new TEMPLATE -o FILE`: the built-in templates, listed or made into a new scenario. */
async function templatesAction(
  action: 'templates' | 'new',
  rest: string[],
  values: { format?: string; output?: string; quiet?: boolean },
  io: CliOutput,
): Promise<number> {
  const { templates, problems } = listTemplates();
  for (const problem of problems) io.err(`${relative(problem.file)}: error: ${problem.message}`);
  if (action === 'templates') {
    if (rest.length > 0) throw new UsageError('library templates takes no name');
    if (values.format === 'json') io.out(JSON.stringify({ templates, problems }, null, 2));
    else
      for (const template of templates)
        io.out(`${template.name}  ${template.title}${template.distribution ? ' (with a distribution)' : ''}\n  ${template.summary}`);
    return problems.length > 0 ? ExitCode.problems : ExitCode.ok;
  }
  if (rest.length !== 1) throw new UsageError('library new takes one template name (library templates lists them)');
  if (!values.output) throw new UsageError('library new needs -o FILE.xosc, the new scenario');
  if (!values.output.toLowerCase().endsWith('.xosc')) throw new UsageError(`-o ${values.output}: the new scenario's name ends in .xosc`);
  const template = templates.find((candidate) => candidate.name === rest[0]);
  if (!template) {
    const suggestion = closestMatch(
      rest[0],
      templates.map((candidate) => candidate.name),
    );
    throw new InputError(
      `no template '${rest[0]}'${suggestion ? `: did you mean '${suggestion}'?` : ''} (modular2simple library templates names them all)`,
    );
  }
  const scenario = path.resolve(values.output);
  let outputs;
  try {
    outputs = templateOutputs(template, scenario);
  } catch (error) {
    throw new InputError((error as Error).message);
  }
  return write(
    outputs.map((output) => ({ ...output, summary: `wrote ${relative(output.target)}` })),
    io,
    values.quiet ?? false,
  );
}

function relative(file: string): string {
  const shown = path.relative(process.cwd(), file);
  return shown.startsWith('..') || path.isAbsolute(shown) ? file : shown;
}

function moduleJson(module: LibraryModule) {
  return {
    name: module.name,
    reference: `${LIBRARY_PREFIX}${module.name}`,
    file: module.file,
    library: module.library.label,
    example: module.example ?? null,
    picture: module.picture ?? null,
    title: module.title,
    group: module.group,
    doc: module.summary,
    maneuverGroup: module.maneuverGroup,
    actor: module.actor,
    parameters: module.parameters,
    hides: module.hides,
  };
}

function printProblems(listing: LibraryListing, io: CliOutput): void {
  for (const problem of listing.problems)
    io.err(`${relative(problem.file)}${problem.line ? `:${problem.line}` : ''}: error: ${problem.message}`);
}

function showText(module: LibraryModule): string {
  const lines = [
    `${LIBRARY_PREFIX}${module.name}: ${module.title} (${module.group})`,
    `  ${module.summary}`,
    `  file: ${relative(module.file)} (${module.library.label} library)`,
    ...module.hides.map((file) => `  hides: ${relative(file)} (a later library's module of the same name)`),
    `  group: ${module.maneuverGroup}; actor: ${module.actor.name}${module.actor.about ? `, ${module.actor.about}` : ''}`,
    '  keys:',
  ];
  const keyWidth = Math.max(...module.parameters.map((parameter) => parameter.key.length));
  for (const parameter of module.parameters) {
    const unit = parameter.unit ? ` ${parameter.unit}` : '';
    const range = parameter.range ? `, ${parameter.range}${unit}` : '';
    lines.push(
      `    ${parameter.key.padEnd(keyWidth)}  ${parameter.name}: ${parameter.about} (default ${parameter.defaultValue ?? '(none)'}${parameter.defaultValue !== undefined ? unit : ''}${range})`,
    );
  }
  lines.push(`  example: ${module.example ? relative(module.example) : '(none)'}`);
  lines.push(`  picture: ${module.picture ? relative(module.picture) : '(none)'}`);
  return lines.join('\n');
}

async function libraryCommand(args: string[], io: CliOutput): Promise<number> {
  const { values, positionals } = parseCommandLine(args, OPTIONS);
  const format = values.format ?? 'text';
  if (format !== 'text' && format !== 'json') throw new UsageError(`--format takes text or json, not '${format}'`);
  const [action, ...rest] = positionals;
  if (action === 'templates' || action === 'new') return templatesAction(action, rest, values, io);
  if (values.output) throw new UsageError('-o is for library new');
  const libraries = libraryFolders(values.library ?? []);
  if (action === 'path') {
    if (rest.length > 0) throw new UsageError('library path takes no name');
    if (format === 'json') io.out(JSON.stringify(libraries, null, 2));
    else for (const library of libraries) io.out(library.folder);
    return ExitCode.ok;
  }
  if (action !== 'list' && action !== 'show')
    throw new UsageError(
      action
        ? `unknown library action '${action}' (list, show NAME, path, templates or new TEMPLATE)`
        : 'library takes list, show NAME, path, templates or new TEMPLATE',
    );
  if (action === 'list' && rest.length > 0) throw new UsageError('library list takes no name');
  if (action === 'show' && rest.length !== 1) throw new UsageError('library show takes one module name');
  const listing = await listLibraries(cliFileSystem, libraries);
  printProblems(listing, io);
  const code = listing.problems.length > 0 ? ExitCode.problems : ExitCode.ok;
  if (action === 'list') {
    if (format === 'json') {
      io.out(JSON.stringify({ libraries, modules: listing.modules.map(moduleJson), problems: listing.problems }, null, 2));
      return code;
    }
    if (listing.modules.length === 0) io.err('no library module found (modular2simple library path lists the folders searched)');
    const width = Math.max(0, ...listing.modules.map((module) => module.name.length));
    let group: string | undefined;
    for (const module of [...listing.modules].sort((a, b) => a.group.localeCompare(b.group) || a.name.localeCompare(b.name))) {
      if (module.group !== group) {
        group = module.group;
        io.out(`${group}:`);
      }
      const hides = module.hides.length > 0 ? ` (hides ${module.hides.map(relative).join(', ')})` : '';
      io.out(`  ${module.name.padEnd(width)}  ${module.title}: ${module.summary}${hides}`);
      io.out(`  ${''.padEnd(width)}  ${relative(module.file)}; example ${module.example ? relative(module.example) : '(none)'}`);
    }
    return code;
  }
  const { module, suggestion } = findModule(listing, rest[0]);
  if (!module)
    throw new InputError(
      `no library module '${rest[0]}'${suggestion ? `: did you mean '${suggestion}'?` : ''} (modular2simple library list names them all)`,
    );
  io.out(format === 'json' ? JSON.stringify(moduleJson(module), null, 2) : showText(module));
  return code;
}

export const LIBRARY: CliCommand = { help: LIBRARY_HELP, run: libraryCommand };
