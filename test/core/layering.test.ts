import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as ts from 'typescript';
import { repoRoot } from '../support/paths';

const SOURCE_FOLDERS = ['server/src', 'client/src', 'common/src'];

/** Every .ts file under the source folders, as a path relative to the repository with '/'. */
function sourceFiles(): string[] {
  const files: string[] = [];
  const visit = (folder: string) => {
    for (const entry of fs.readdirSync(path.join(repoRoot, folder), { withFileTypes: true })) {
      const relative = `${folder}/${entry.name}`;
      if (entry.isDirectory()) visit(relative);
      else if (entry.name.endsWith('.ts')) files.push(relative);
    }
  };
  SOURCE_FOLDERS.forEach(visit);
  return files.sort();
}

/** The file a relative specifier names: x.ts or x/index.ts; undefined for a file that is no TypeScript source. */
function resolve(from: string, specifier: string, known: Set<string>): string | undefined {
  const base = path.posix.normalize(path.posix.join(path.posix.dirname(from), specifier));
  return [base, `${base}.ts`, `${base}/index.ts`].find((candidate) => known.has(candidate));
}

/**
 * Each file's relative imports, resolved: `import`, `import type`, `export ... from`, `import('./x')` and
 * `require('./x')`, read by TypeScript's own pre-processor (so an import-shaped line in a string is none).
 */
function importGraph(): Map<string, string[]> {
  const files = sourceFiles();
  const known = new Set(files);
  const graph = new Map<string, string[]>();
  for (const file of files) {
    const text = fs.readFileSync(path.join(repoRoot, file), 'utf8');
    const imported = new Set<string>();
    for (const { fileName } of ts.preProcessFile(text, true, true).importedFiles) {
      if (!fileName.startsWith('.')) continue;
      const target = resolve(file, fileName, known);
      // A relative import of no source file here (a JSON file, say) is no edge of this graph, but it must name a file.
      if (!target) {
        const base = path.join(repoRoot, path.dirname(file), fileName);
        assert.ok(
          [base, `${base}.ts`, path.join(base, 'index.ts')].some((candidate) => fs.existsSync(candidate)),
          `${file} imports '${fileName}', which names no file`,
        );
        continue;
      }
      imported.add(target);
    }
    graph.set(file, [...imported].sort());
  }
  return graph;
}

/** The strongly connected components of more than one file, or of one file importing itself (Tarjan). */
function circles(graph: Map<string, string[]>): string[][] {
  const index = new Map<string, number>();
  const lowest = new Map<string, number>();
  const stack: string[] = [];
  const onStack = new Set<string>();
  const found: string[][] = [];
  const connect = (file: string) => {
    index.set(file, index.size);
    lowest.set(file, index.get(file)!);
    stack.push(file);
    onStack.add(file);
    for (const next of graph.get(file) ?? []) {
      if (!index.has(next)) {
        connect(next);
        lowest.set(file, Math.min(lowest.get(file)!, lowest.get(next)!));
      } else if (onStack.has(next)) lowest.set(file, Math.min(lowest.get(file)!, index.get(next)!));
    }
    if (lowest.get(file) !== index.get(file)) return;
    const component: string[] = [];
    let member: string;
    do {
      member = stack.pop()!;
      onStack.delete(member);
      component.push(member);
    } while (member !== file);
    if (component.length > 1 || graph.get(file)!.includes(file)) found.push(component.sort());
  };
  for (const file of graph.keys()) if (!index.has(file)) connect(file);
  return found;
}

/** One shortest loop through a circle's first file, as `a -> b -> a`. */
function loopThrough(circle: string[], graph: Map<string, string[]>): string {
  const members = new Set(circle);
  const start = circle[0];
  const cameFrom = new Map<string, string>();
  const queue = [start];
  while (queue.length > 0) {
    const file = queue.shift()!;
    for (const next of graph.get(file)!) {
      if (!members.has(next) || cameFrom.has(next)) continue;
      cameFrom.set(next, file);
      if (next === start) {
        const loop = [start];
        for (let step = file; step !== start; step = cameFrom.get(step)!) loop.unshift(step);
        return [start, ...loop].join(' -> ');
      }
      queue.push(next);
    }
  }
  throw new Error(`no loop through ${start} in its own circle`);
}

/**
 * The imports between the parts of each folder: a part is a folder inside it (with everything below) or a
 * file directly in it; each edge keeps one import that makes it, as `file -> file`.
 */
function folderGraphs(graph: Map<string, string[]>): Map<string, Map<string, Map<string, string>>> {
  const folders = new Set<string>();
  for (const file of graph.keys()) {
    for (let folder = path.posix.dirname(file); folder !== '.'; folder = path.posix.dirname(folder)) folders.add(folder);
  }
  const byFolder = new Map<string, Map<string, Map<string, string>>>();
  for (const folder of folders) {
    const partOf = (file: string) =>
      file.startsWith(`${folder}/`) ? `${folder}/${file.slice(folder.length + 1).split('/')[0]}` : undefined;
    const parts = new Map<string, Map<string, string>>();
    for (const [file, imports] of graph) {
      const from = partOf(file);
      if (!from) continue;
      if (!parts.has(from)) parts.set(from, new Map());
      for (const target of imports) {
        const to = partOf(target);
        if (to && to !== from && !parts.get(from)!.has(to)) parts.get(from)!.set(to, `${file} -> ${target}`);
      }
    }
    byFolder.set(folder, parts);
  }
  return byFolder;
}

/**
 * Each circle among the parts of a folder that holds a folder (a circle of files alone is a file cycle): its
 * parts, and each import between two of them with one import that makes it, so two folders that import
 * each other are named with one import each way.
 */
function folderCircles(graph: Map<string, string[]>): string[] {
  const found: string[] = [];
  for (const [folder, parts] of folderGraphs(graph)) {
    const partGraph = new Map([...parts].map(([part, imports]) => [part, [...imports.keys()].sort()]));
    for (const circle of circles(partGraph)) {
      if (circle.every((part) => graph.has(part))) continue;
      const steps = circle.flatMap((from) =>
        partGraph
          .get(from)!
          .filter((to) => circle.includes(to))
          .map((to) => `    ${from} -> ${to}: ${parts.get(from)!.get(to)}`),
      );
      found.push([`in ${folder}, a circle of ${circle.join(', ')}:`, ...steps].join('\n'));
    }
  }
  return found;
}

/**
 * The layer pictures of ARCHITECTURE.md's Layers section: for each folder drawn (a line `server/src/` or
 * `server/src/core/` at the start), its rows top to bottom, each the parts it names (`a.ts, b/`).
 */
function layerPictures(markdown: string): Map<string, string[][]> {
  const section = markdown.slice(markdown.indexOf('## Layers'), markdown.indexOf('\n## ', markdown.indexOf('## Layers') + 1));
  const pictures = new Map<string, string[][]>();
  let rows: string[][] | undefined;
  let folder = '';
  for (const line of section.split('\n')) {
    const heading = /^(server\/src(?:\/core)?)\/\s*$/.exec(line);
    if (heading) {
      folder = heading[1];
      rows = [];
      pictures.set(folder, rows);
    } else if (/^\S/.test(line)) rows = undefined;
    else if (rows && /^ {2}\S/.test(line)) {
      rows.push(
        line
          .trim()
          .split(/\s{2,}/)[0]
          .split(/,\s*/)
          .map((part) => `${folder}/${part.replace(/\/$/, '')}`),
      );
    }
  }
  return pictures;
}

/** What is wrong with the pictures: a folder not drawn, a part that is not there, a part importing one on its own line or above. */
function pictureErrors(graph: Map<string, string[]>, pictures: Map<string, string[][]>): string[] {
  const errors: string[] = [];
  const byFolder = folderGraphs(graph);
  for (const [folder, rows] of pictures) {
    const parts = byFolder.get(folder) ?? new Map<string, Map<string, string>>();
    const rowOf = new Map(rows.flatMap((row, index) => row.map((part) => [part, index] as const)));
    for (const part of new Set(rows.flat()))
      if (rows.flat().filter((drawn) => drawn === part).length > 1) errors.push(`${folder}: ${part} is drawn twice`);
    for (const part of parts.keys()) if (!graph.has(part) && !rowOf.has(part)) errors.push(`${folder}: the folder ${part} is not drawn`);
    for (const [part, row] of rowOf) {
      if (!parts.has(part)) {
        errors.push(`${folder}: ${part} is drawn but not there`);
        continue;
      }
      for (const [target, example] of parts.get(part)!) {
        const below = rowOf.get(target);
        if (below !== undefined && below <= row)
          errors.push(`${folder}: ${part} is drawn above or beside ${target}, which it imports (${example})`);
      }
    }
  }
  return errors;
}

describe('layering: the imports of server/src, client/src and common/src', () => {
  let graph: Map<string, string[]>;
  before(() => {
    graph = importGraph();
  });

  it('reads the imports of every source file, each kind of them', () => {
    assert.ok(graph.size > 200, `only ${graph.size} files read`);
    const importsOf = (file: string) => graph.get(file) ?? [];
    assert.ok(importsOf('server/src/cli.ts').includes('server/src/cli/common.ts'));
    // A dynamic import counts: the CLI loads each command's file when it runs.
    assert.ok(importsOf('server/src/cli.ts').includes('server/src/cli/batch.ts'));
    // So does a re-export (`export * from`), and a folder resolves to its index.ts.
    assert.ok(importsOf('server/src/core/semantics/index.ts').includes('server/src/core/semantics/values.ts'));
    assert.ok(importsOf('server/src/core/semantics/roadFiles.ts').includes('server/src/core/sources/index.ts'));
  });

  it('has no import cycle', () => {
    const loops = circles(graph).map((circle) => `${loopThrough(circle, graph)}  (a circle of ${circle.length}: ${circle.join(', ')})`);
    assert.deepEqual(loops, [], `import cycles:\n${loops.join('\n')}`);
  });

  it('has no import cycle between folders: no two parts of a folder (a folder inside it, a file in it) import each other', () => {
    const loops = folderCircles(graph);
    assert.deepEqual(loops, [], `folders that import each other:\n${loops.join('\n')}`);
  });

  it("matches ARCHITECTURE.md's layer pictures: every folder drawn, each part above what it imports", () => {
    const pictures = layerPictures(fs.readFileSync(path.join(repoRoot, 'ARCHITECTURE.md'), 'utf8'));
    assert.deepEqual([...pictures.keys()], ['server/src', 'server/src/core']);
    assert.ok(pictures.get('server/src/core')!.flat().includes('server/src/core/semantics'));
    const errors = pictureErrors(graph, pictures);
    assert.deepEqual(errors, [], `ARCHITECTURE.md's layer pictures:\n${errors.join('\n')}`);
    // A picture drawn upside down fails, naming the import.
    const upsideDown = new Map([...pictures].map(([folder, rows]) => [folder, [...rows].reverse()]));
    assert.match(
      pictureErrors(graph, upsideDown).join('\n'),
      /server\/src\/core\/xml is drawn above or beside server\/src\/core\/text\.ts, which it imports/,
    );
  });

  it('names the folders of a folder cycle and one import each way', () => {
    const cyclic = new Map([
      ['x/a/one.ts', ['x/b/two.ts']],
      ['x/b/two.ts', []],
      ['x/b/three.ts', ['x/a/four.ts']],
      ['x/a/four.ts', []],
      ['x/c.ts', ['x/a/one.ts']],
    ]);
    assert.deepEqual(folderCircles(cyclic), [
      ['in x, a circle of x/a, x/b:', '    x/a -> x/b: x/a/one.ts -> x/b/two.ts', '    x/b -> x/a: x/b/three.ts -> x/a/four.ts'].join('\n'),
    ]);
    // Files alone in a loop are the file test's; a folder and a file beside it that import each other are a folder cycle.
    cyclic.set('x/b/two.ts', ['x/c.ts']);
    cyclic.set('x/b/three.ts', []);
    assert.deepEqual(folderCircles(cyclic), [
      [
        'in x, a circle of x/a, x/b, x/c.ts:',
        '    x/a -> x/b: x/a/one.ts -> x/b/two.ts',
        '    x/b -> x/c.ts: x/b/two.ts -> x/c.ts',
        '    x/c.ts -> x/a: x/c.ts -> x/a/one.ts',
      ].join('\n'),
    ]);
  });

  it('imports server/src/cli/ only from the CLI itself: the batch runner and the rest sit below it', () => {
    const upward = [...graph]
      .filter(([file]) => file !== 'server/src/cli.ts' && !file.startsWith('server/src/cli/'))
      .flatMap(([file, imports]) =>
        imports.filter((target) => target.startsWith('server/src/cli/')).map((target) => `${file} -> ${target}`),
      );
    assert.deepEqual(upward, []);
  });
});
