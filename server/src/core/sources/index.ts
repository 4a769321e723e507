/** Where scenario files live and how names written in them resolve (SPEC 3). */
export { normalizeEntryName, readPackageBytes } from '../../../../common/src/packageEntries';
export type { PackageContents } from '../../../../common/src/packageEntries';
export { splitScenarioPath } from '../../../../common/src/scenarioPath';
export { baseName, childRef, diskRef, displayRef, refId, sameRef, SourceError } from './ref';
export type { SourceRef } from './ref';
export { boundedBytes, FileReadError, KindCache, nodeFileSystem, openError, readBufferFor } from './host';
export type { FileKind, FileSystemHost } from './host';
export { DEFAULT_LIMITS, DEFAULT_PACKAGE_LIMITS } from './limits';
export type { Limits, PackageLimits } from './limits';
export { SizedCache } from './sizedCache';
export type { FolderOptions, LibraryFolder, LookupPlace, Resolution } from './resolution';
export { LIBRARY_PREFIX, libraryFileName } from './resolution';
export { ScenarioStore } from './store';
export type { StoreOptions } from './store';
