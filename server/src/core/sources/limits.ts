import { DEFAULT_PACKAGE_LIMITS as PACKAGE_BOUNDS, PackageLimits } from '../../../../common/src/packageEntries';

export type { PackageLimits } from '../../../../common/src/packageEntries';

/** Bounds on what one run (a flatten, a check, an index) may read, unpack and produce. */
export interface Limits extends PackageLimits {
  /** Characters of one flattened result. */
  maxFlattenedChars: number;
  /** Files in one chain of references (nested packages included). */
  maxDepth: number;
}

export const DEFAULT_LIMITS: Limits = {
  ...PACKAGE_BOUNDS,
  maxFlattenedChars: 8 * 1024 * 1024,
  maxDepth: 64,
};

/** @deprecated the package bounds are part of Limits. */
export const DEFAULT_PACKAGE_LIMITS: PackageLimits = DEFAULT_LIMITS;
