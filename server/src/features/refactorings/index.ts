import { extractToCatalogRefactoring } from './extractToCatalog';
import { extractToSimpleRefactoring } from './extractToSimple';
import { inlineRefactoring } from './inline';
import { insertLibraryModuleRefactoring } from './insertLibraryModule';
import { makeOverridableRefactoring } from './makeOverridable';
import { Refactoring } from './refactoring';

export type { ClientEdits, Refactoring, RefactoringTarget } from './refactoring';
export { NO_CLIENT_EDITS, refactoringTarget } from './refactoring';
export { extractGroupEdit } from './extractToSimple';

/** Every refactoring, in the order their actions are listed. */
export const REFACTORINGS: readonly Refactoring[] = [
  extractToSimpleRefactoring,
  extractToCatalogRefactoring,
  makeOverridableRefactoring,
  inlineRefactoring,
  insertLibraryModuleRefactoring,
];
