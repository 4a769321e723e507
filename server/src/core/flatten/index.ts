/*
 * Flattening modular scenarios (SPEC 4, 5 and 11), one job per file:
 *   types.ts        the flattened-source data types
 *   origin.ts       where an element of a flattened text was written
 *   report.ts       problems at offsets
 *   edits.ts        text edits: copying a group, stripping parameterAttributes
 *   link.ts         following one ScenarioReference to the groups it imports
 *   render.ts       writing the flattened text
 *   carry.ts        what the output needs carried from the sources
 *   rebase.ts       the file paths of an output rebased onto its folder (SPEC 11.6)
 *   besideOutput.ts which packaged files a writer may write beside the output
 *   checks.ts       checks of a file read and of the output
 *   outputSchema.ts the schema check of the output
 *   flattener.ts    the Flattener, which reads, links and renders files and caches them
 *   storyboardMap.ts each storyboard element of a flattened scenario with esmini's path and its place in the sources
 */
export { Flattener } from './flattener';
export { copiedFrom, declarationLocation, originOf } from './origin';
export { describeChain } from './report';
export { parameterAttributeSpans, reindent, stripParameterAttributes } from './edits';
export { besideOutputWritable } from './besideOutput';
export { FILE_PATH_ELEMENTS, filePathSites, parameterPackagedFiles, pathBaseOf, rebaseFlattened, rebasePaths } from './rebase';
export type { FilePathSite, PathRebase, RebaseFinding, RebaseRequest, ResolvedPath } from './rebase';
export { outputSchemaProblems, overrideValueProblems } from './outputSchema';
export { OVERRIDE_PROBLEM_CODES } from './types';
export type {
  Addition,
  AnalysisResult,
  FlatSource,
  FlattenOptions,
  FlattenResult,
  Insertion,
  LinkedGroupReference,
  LinkedReference,
  PackagedFile,
  SchemaOptions,
} from './types';
