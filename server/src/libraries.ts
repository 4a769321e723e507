import * as fs from 'node:fs';
import * as path from 'node:path';
import { splitScenarioPath } from '../../common/src/scenarioPath';
import { LibraryFolder } from './core/sources';
import { instantiateDistribution, instantiateTemplate, readTemplate, ScenarioTemplate, templateRoad } from './core/templates';

/**
 * `library/` of the project this program runs from (the nearest folder above it with a package.json: the
 * repository for `dist/` and for the sources, the extension's folder for the .vsix), the library shipped with it.
 */
export function builtInLibraryFolder(from: string = __dirname): string | undefined {
  for (let folder = from, level = 0; level < 4; folder = path.dirname(folder), level++) {
    if (fs.existsSync(path.join(folder, 'package.json'))) {
      const library = path.join(folder, 'library');
      return fs.existsSync(library) ? library : undefined;
    }
  }
  return undefined;
}

/**
 * The libraries `library:NAME` is looked up in, in order: the user's folders (as given, then SCENARIO_LIBRARY_PATH's),
 * then the built-in library; a module of the user's hides a built-in one of the same name.
 */
export function libraryFolders(
  userFolders: readonly string[],
  environment: Readonly<Record<string, string | undefined>> = process.env,
  builtIn: string | undefined = builtInLibraryFolder(),
): LibraryFolder[] {
  const user = [...userFolders.map((folder) => path.resolve(folder)), ...splitScenarioPath(environment.SCENARIO_LIBRARY_PATH)];
  const folders: LibraryFolder[] = [];
  for (const folder of user) if (!folders.some((known) => known.folder === folder)) folders.push({ folder, label: 'user' });
  if (builtIn && !folders.some((known) => known.folder === builtIn)) folders.push({ folder: builtIn, label: 'built-in' });
  return folders;
}

/** The built-in library's templates (library/templates/), and each file that is no template with why. */
export function listTemplates(library: string | undefined = builtInLibraryFolder()): {
  templates: ScenarioTemplate[];
  problems: { file: string; message: string }[];
} {
  const templates: ScenarioTemplate[] = [];
  const problems: { file: string; message: string }[] = [];
  const folder = library ? path.join(library, 'templates') : undefined;
  if (!folder || !fs.existsSync(folder))
    return { templates, problems: [{ file: folder ?? 'library/templates', message: 'no templates folder' }] };
  for (const entry of fs.readdirSync(folder).sort()) {
    if (!entry.endsWith('.xosc') || entry.endsWith('.distribution.xosc')) continue;
    const file = path.join(folder, entry);
    const read = readTemplate(fs.readFileSync(file, 'utf8'), file);
    if (read.template) templates.push(read.template);
    else problems.push({ file, message: read.problem ?? 'not a template' });
  }
  return { templates, problems };
}

/**
 * The files a new scenario from a template is made of, none written yet: the scenario at `scenario`, the template's
 * road beside it (left out when a file of that name with the same content is there already) and, for a template with
 * a distribution, `NAME.distribution.xosc` beside it naming the scenario. A file that exists is never replaced: it is
 * an error naming the file.
 */
export function templateOutputs(template: ScenarioTemplate, scenario: string): { target: string; data: string }[] {
  const text = fs.readFileSync(template.file, 'utf8');
  const road = templateRoad(text);
  const outputs: { target: string; data: string }[] = [];
  let roadFile = road ?? '';
  if (road) {
    const source = path.resolve(path.dirname(template.file), road);
    const target = path.join(path.dirname(scenario), path.basename(source));
    const data = fs.readFileSync(source, 'utf8');
    roadFile = path.basename(source);
    if (!fs.existsSync(target)) outputs.push({ target, data });
    else if (fs.readFileSync(target, 'utf8') !== data)
      throw new Error(`${target} exists and is not the template's road: move it away, or create the scenario in another folder`);
  }
  outputs.unshift({ target: scenario, data: instantiateTemplate(text, template, roadFile) });
  if (template.distribution) {
    const distribution = fs.readFileSync(path.join(path.dirname(template.file), template.distribution), 'utf8');
    outputs.push({
      target: scenario.replace(/\.xosc$/i, '') + '.distribution.xosc',
      data: instantiateDistribution(distribution, path.basename(scenario)),
    });
  }
  for (const output of outputs)
    if (fs.existsSync(output.target)) throw new Error(`${output.target} exists: nothing was written (choose another name)`);
  return outputs;
}
