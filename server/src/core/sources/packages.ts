import { PackageContents, readPackageBytes } from '../../../../common/src/packageEntries';
import { InflateBudget } from '../zip';
import { Limits } from './limits';
import { refId, SourceError, SourceRef } from './ref';
import { SizedCache } from './sizedCache';

function contentsSize(contents: PackageContents): number {
  let size = 0;
  for (const bytes of contents.entries.values()) size += bytes.length;
  return size;
}

/**
 * The unpacked packages of a store: each read once (concurrent readers share the read), kept up to
 * a size, a failure remembered until the next run; what a run unpacks is charged to its budget.
 */
export class PackageCache {
  /** What one run may still unpack; see resetBudget. */
  private budget: InflateBudget;
  private readonly packages: SizedCache<PackageContents>;
  private readonly pendingPackages = new Map<string, Promise<PackageContents>>();
  private readonly failedPackages = new Map<string, Promise<PackageContents>>();

  constructor(
    private readonly limits: Limits,
    cacheBytes: number,
    /** The package file's bytes (on disk or an entry of another package). */
    private readonly readBytes: (ref: SourceRef) => Promise<Uint8Array>,
    /** How messages name a package. */
    private readonly display: (ref: SourceRef) => string,
  ) {
    this.budget = { remaining: limits.maxTotalBytes, limit: limits.maxTotalBytes };
    this.packages = new SizedCache(cacheBytes);
  }

  /** Starts a new run: what it may unpack is counted from zero (packages still cached cost nothing). */
  resetBudget(): void {
    this.budget = { remaining: this.limits.maxTotalBytes, limit: this.limits.maxTotalBytes };
    this.failedPackages.clear();
  }

  /** Bytes of unpacked packages held for reuse. */
  get size(): number {
    return this.packages.size;
  }

  /** Forgets every package whose id passes `below`. */
  invalidate(below: (id: string) => boolean): void {
    this.packages.deleteWhere(below);
    for (const key of [...this.pendingPackages.keys()]) if (below(key)) this.pendingPackages.delete(key);
    for (const key of [...this.failedPackages.keys()]) if (below(key)) this.failedPackages.delete(key);
  }

  /** The entries of the package stored at `ref` (a `.mosc` on disk or inside another package). */
  read(ref: SourceRef): Promise<PackageContents> {
    const id = refId(ref);
    const cached = this.packages.get(id);
    if (cached) return Promise.resolve(cached);
    let pending = this.pendingPackages.get(id) ?? this.failedPackages.get(id);
    if (!pending) {
      const reading = (async () => {
        const bytes = await this.readBytes(ref);
        try {
          return await readPackageBytes(bytes, this.display(ref), this.limits, this.budget);
        } catch (error) {
          throw new SourceError((error as Error).message, ref, 'rebuild the package with `modular2simple pack`', undefined, 'bad-package');
        }
      })();
      pending = reading;
      this.pendingPackages.set(id, reading);
      reading.then(
        (contents) => {
          if (this.pendingPackages.get(id) !== reading) return;
          this.pendingPackages.delete(id);
          this.packages.set(id, contents, contentsSize(contents));
        },
        () => {
          if (this.pendingPackages.get(id) !== reading) return;
          this.pendingPackages.delete(id);
          this.failedPackages.set(id, reading);
        },
      );
    }
    return pending;
  }
}
