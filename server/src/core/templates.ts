/**
 * Scenario templates: mains composed from library modules for common test protocols (`library/templates/`,
 * docs/library.md), each opening with a doc block:
 *
 *     <!-- library template
 *     name: ncap-ccrb
 *     title: Car-to-car rear, braking (Euro NCAP CCRb style)
 *     summary: ...
 *     distribution: alks-cut-in.distribution.xosc      (optional: a ParameterValueDistribution over this file)
 *     -->
 *
 * A new scenario from a template is its text with the road file named beside it (the template names the library's
 * road as `../roads/FILE`), and its distribution, when it has one, naming the new file.
 */
import { pathsFor } from './paths';
import { escapeAttributeValue } from './xml';

export interface ScenarioTemplate {
  name: string;
  file: string;
  title: string;
  summary: string;
  /** The distribution file beside the template (a file name), when the template has one. */
  distribution?: string;
}

const DOC_BLOCK = /<!--\s*library template\b([\s\S]*?)-->/;
const LOGIC_FILE = /(<LogicFile\s+filepath=")([^"]*)(")/;
const SCENARIO_FILE = /(<ScenarioFile\s+filepath=")([^"]*)(")/;

/** The template a file's text describes, or why it is none (a sentence naming what is missing). */
export function readTemplate(text: string, file: string): { template?: ScenarioTemplate; problem?: string } {
  const block = DOC_BLOCK.exec(text);
  if (!block) return { problem: 'no doc block: a template opens with <!-- library template ... --> (docs/library.md)' };
  const fields = new Map<string, string>();
  for (const raw of block[1].split('\n')) {
    const colon = raw.indexOf(':');
    if (colon > 0) fields.set(raw.slice(0, colon).trim(), raw.slice(colon + 1).trim());
  }
  const name = pathsFor(file)
    .basename(file)
    .replace(/\.xosc$/i, '');
  const missing = ['name', 'title', 'summary'].filter((field) => !fields.get(field));
  if (missing.length > 0) return { problem: `the doc block has no ${missing.map((field) => `'${field}:'`).join(', ')}` };
  if (fields.get('name') !== name) return { problem: `the doc block names '${fields.get('name')}', the file '${name}'` };
  const distribution = fields.get('distribution');
  return {
    template: {
      name,
      file,
      title: fields.get('title') ?? '',
      summary: fields.get('summary') ?? '',
      ...(distribution ? { distribution } : {}),
    },
  };
}

/** The road file a template names (`../roads/straight_1000m.xodr`), as written. */
export function templateRoad(text: string): string | undefined {
  return LOGIC_FILE.exec(text)?.[2];
}

/**
 * A new scenario's text from a template's: the doc block becomes a line saying where it came from, and the road
 * is named as `roadFile` (relative to the new scenario).
 */
export function instantiateTemplate(text: string, template: ScenarioTemplate, roadFile: string): string {
  return text
    .replace(DOC_BLOCK, `<!-- From the template ${template.name}: ${template.title}. -->`)
    .replace(LOGIC_FILE, (_, open: string, __: string, close: string) => `${open}${escapeAttributeValue(roadFile)}${close}`);
}

/** A template's distribution, naming the new scenario (`scenarioFile`, relative to the distribution) as its ScenarioFile. */
export function instantiateDistribution(text: string, scenarioFile: string): string {
  return text.replace(
    SCENARIO_FILE,
    (_, open: string, __: string, close: string) => `${open}${escapeAttributeValue(scenarioFile)}${close}`,
  );
}
