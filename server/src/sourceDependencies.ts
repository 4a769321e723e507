/**
 * The files each shared source depends on (itself, and every file its references and catalogs read,
 * transitively) and the reverse index: the sources depending on each file. A change finds the sources it
 * makes stale from the files it names, instead of walking every shared source on each keystroke
 * (`AnalysisDatabase.changed`). A source still being read has no dependencies yet: it is listed apart,
 * and any change makes it stale.
 */
export class SourceDependencies {
  private readonly ofSource = new Map<string, string[]>();
  /** Each file, and the sources depending on it (a source always depends on itself). */
  private readonly dependents = new Map<string, Set<string>>();
  /** How many files of `dependents` lie below each folder or package path: a change of a path with none below it walks nothing. */
  private readonly filesBelow = new Map<string, number>();
  private readonly reading = new Set<string>();
  /**
   * Sources forgotten (made stale) whose links stay in `dependents`, left out of every answer, until they are
   * read again: the main file read again after each keystroke mostly depends on the same files, and linking
   * its 400 dependencies again would cost more than the walk of every source the index replaces.
   */
  private readonly forgotten = new Map<string, string[]>();

  /** The files a source read depends on, as recorded when its read ended. */
  get(id: string): string[] | undefined {
    return this.ofSource.get(id);
  }

  /** Whether the read of `id` ended and its dependencies are known. */
  has(id: string): boolean {
    return this.ofSource.has(id);
  }

  /** A read of `id` began: its dependencies are unknown until `set`. */
  readStarted(id: string): void {
    this.reading.add(id);
  }

  /** A read of `id` failed: the source is forgotten, nothing is recorded. */
  readFailed(id: string): void {
    this.reading.delete(id);
  }

  set(id: string, dependencies: string[]): void {
    this.reading.delete(id);
    const linked = this.ofSource.get(id) ?? this.forgotten.get(id);
    this.forgotten.delete(id);
    if (linked && sameIds(linked, dependencies)) {
      // The same list as before, so those who compare lists by identity (`AnalysisDatabase.rememberOpenReads`) see no change.
      this.ofSource.set(id, linked);
      return;
    }
    this.ofSource.set(id, dependencies);
    if (linked) {
      this.unlink(id, id);
      for (const dependency of linked) this.unlink(dependency, id);
    }
    this.link(id, id);
    for (const dependency of dependencies) this.link(dependency, id);
  }

  delete(id: string): void {
    this.reading.delete(id);
    const dependencies = this.ofSource.get(id);
    if (!dependencies) return;
    this.ofSource.delete(id);
    this.forgotten.set(id, dependencies);
  }

  clear(): void {
    this.ofSource.clear();
    this.forgotten.clear();
    this.dependents.clear();
    this.filesBelow.clear();
    this.reading.clear();
  }

  /**
   * The sources a change of `changedIds` (file ids, or disk paths of files and folders) makes stale: each
   * named file, those depending on it or on a file below it (a folder, a package's entries), and every
   * source still being read.
   */
  staleAfter(changedIds: string[]): Set<string> {
    const stale = new Set(this.reading);
    const add = (file: string) => {
      stale.add(file);
      const dependents = this.dependents.get(file);
      if (dependents) for (const dependent of dependents) if (!this.forgotten.has(dependent)) stale.add(dependent);
    };
    for (const changed of changedIds) {
      add(changed);
      if (!this.filesBelow.has(changed)) continue;
      const folder = changed + '/';
      for (const file of this.dependents.keys()) if (file.startsWith(folder)) add(file);
    }
    return stale;
  }

  private link(file: string, dependent: string): void {
    const dependents = this.dependents.get(file);
    if (dependents) {
      dependents.add(dependent);
      return;
    }
    this.dependents.set(file, new Set([dependent]));
    for (const folder of foldersOf(file)) this.filesBelow.set(folder, (this.filesBelow.get(folder) ?? 0) + 1);
  }

  private unlink(file: string, dependent: string): void {
    const dependents = this.dependents.get(file);
    if (!dependents?.delete(dependent) || dependents.size > 0) return;
    this.dependents.delete(file);
    for (const folder of foldersOf(file)) {
      const count = (this.filesBelow.get(folder) ?? 0) - 1;
      if (count > 0) this.filesBelow.set(folder, count);
      else this.filesBelow.delete(folder);
    }
  }
}

/** The paths `id` lies below, as `AnalysisDatabase.changed` names folders: each prefix ending before a `/`. */
function* foldersOf(id: string): Generator<string> {
  for (let slash = id.lastIndexOf('/'); slash > 0; slash = id.lastIndexOf('/', slash - 1)) yield id.slice(0, slash);
}

function sameIds(a: string[], b: string[]): boolean {
  if (a.length !== b.length) return false;
  for (let index = 0; index < a.length; index++) if (a[index] !== b[index]) return false;
  return true;
}
