import * as fs from 'node:fs';
import * as path from 'node:path';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { FixContext, ParameterScopes, RegisteredDiagnostic, RelatedPlace } from '../../../server/src/core/diagnostics';
import { schemaProblems } from '../../../server/src/core/diagnostics/schemaFindings';
import { SchemaCheckMemory } from '../../../server/src/core/schema/problems';
import { applyEdits } from '../../support/textEdits';
import { parseXml } from '../../../server/src/core/xml';
import { Flattener } from '../../../server/src/core/flatten';
import { Problem } from '../../../server/src/core/problems';
import { Simulator } from '../../../server/src/core/profiles/simulators';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../../server/src/core/semantics';
import { diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { temporaryWorkspace } from '../../support/workspace';

export const RANGE = { start: { line: 0, character: 1 }, end: { line: 0, character: 4 } };

/**
 * What a module's fix is given: `data`, a document of `text` with the problem at `range`, a related place
 * and the parameter scopes of the file's analysis where they are given.
 */
export function fixContext(
  data: unknown,
  related?: Partial<RelatedPlace>,
  text = '<a/>',
  range = RANGE,
  parameters?: ParameterScopes,
): FixContext<unknown> {
  const document = TextDocument.create('file:///main.xosc', 'xml', 0, text);
  return {
    data,
    document,
    range,
    parsed: async () => parseXml(document.getText()),
    schemaVersion: 'auto',
    parameters: async () => parameters,
    related: related && {
      range: RANGE,
      sameDocument: false,
      fileName: 'simple.xosc',
      editable: async () => true,
      text: async () => undefined,
      ...related,
    },
  };
}

/**
 * The problems of the document checks (core/semantics) for `scenario.xosc` of `text`, written beside `files` in a workspace
 * of its own; with `simulator`, that simulator's checks too.
 */
export async function semanticProblemsOf(text: string, files: Record<string, string> = {}, simulator?: Simulator): Promise<Problem[]> {
  const root = temporaryWorkspace({ 'scenario.xosc': text, ...files });
  try {
    const semantics = await analyzeDocument(
      diskRef(path.join(root, 'scenario.xosc')),
      parseXml(text),
      new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })),
      false,
      simulator,
    );
    return semanticProblems(semantics);
  } finally {
    fs.rmSync(root, { recursive: true, force: true });
  }
}

/** What a problem says, apart from where: what a module's wording returns. */
export function wordingOf({ severity, code, message, hint }: Problem): Pick<Problem, 'severity' | 'code' | 'message' | 'hint'> {
  return hint === undefined ? { severity, code, message } : { severity, code, message, hint };
}

/** The problems an analysis of `main` reports, its `files` written in a workspace of their own. */
export async function analysisProblemsOf(files: Record<string, string>, main = 'main.xosc'): Promise<Problem[]> {
  const root = temporaryWorkspace(files);
  try {
    return (await new Flattener(new ScenarioStore({ root })).analyze(diskRef(path.join(root, main)))).problems;
  } finally {
    fs.rmSync(root, { recursive: true, force: true });
  }
}

/** The schema check's problems of `text` (a file named main.xosc, the version its FileHeader names). */
export function schemaProblemsOf(text: string): Problem[] {
  return schemaProblems(diskRef('/virtual/main.xosc'), parseXml(text), new SchemaCheckMemory());
}

/** `text` after the first problem of `code` the schema check finds is fixed by `definition`'s first fix; undefined without one. */
export async function schemaFixed(text: string, definition: RegisteredDiagnostic): Promise<{ title: string; text: string } | undefined> {
  const problem = schemaProblemsOf(text).find((candidate) => candidate.code === definition.code);
  if (!problem)
    throw new Error(
      `no ${definition.code} in ${schemaProblemsOf(text)
        .map((found) => found.code)
        .join(', ')}`,
    );
  const [fix] = (await definition.fixes?.(fixContext(problem.data, undefined, text, problem.range))) ?? [];
  if (!fix) return undefined;
  const edits = fix.edits.map((edit) => ({ range: edit.range, newText: edit.newText }));
  return { title: fix.title, text: applyEdits(text, edits) };
}
