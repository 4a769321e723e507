import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { ANALYSIS_DATABASE, cachesTable } from '../../server/src/database';

const repoRoot = path.resolve(__dirname, '..', '..');
const sourceRoot = path.join(repoRoot, 'server', 'src');

function sourceFiles(folder = sourceRoot): string[] {
  return fs.readdirSync(folder, { withFileTypes: true }).flatMap((entry) => {
    const full = path.join(folder, entry.name);
    return entry.isDirectory() ? sourceFiles(full) : entry.name.endsWith('.ts') ? [full] : [];
  });
}

/** Issue 25: one analysis database owns every piece of derived state, each memo declared once. */
describe('server: the analysis database declares every memo', () => {
  const files = sourceFiles().map((file) => ({
    file: path.relative(sourceRoot, file).split(path.sep).join('/'),
    text: fs.readFileSync(file, 'utf8'),
  }));

  it('no module keeps a WeakMap of its own: each asks the database for its declared memo, by a name no other module asks for', () => {
    const own = files.flatMap(({ file, text }) =>
      text
        .split('\n')
        .filter((line) => /^\s*(export\s+)?(const|let|private|readonly|static)\b.*=\s*new WeakMap\b/.test(line))
        .map((line) => `${file}: ${line.trim()}`),
    );
    assert.deepEqual(own, [], 'declare the memo in core/memos.ts or database.ts and ask for it with coreMemo or serverMemo');
    const asked = files.flatMap(({ file, text }) =>
      [...text.matchAll(/\b(?:coreMemo|serverMemo)<[^(]*>\('(\w+)'\)/g)].map((match) => ({ file, name: match[1] })),
    );
    assert.ok(asked.length >= 20, `${asked.length} memos asked for`);
    const twice = asked.filter((one, index) => asked.findIndex((other) => other.name === one.name) !== index);
    assert.deepEqual(twice, [], 'a memo asked for by two modules');
    for (const { name } of asked) assert.ok(name in ANALYSIS_DATABASE, `memo '${name}' is declared`);
  });

  it('each declaration names the modules it lives in', () => {
    for (const [name, memo] of Object.entries(ANALYSIS_DATABASE)) {
      const modules = [...memo.where.matchAll(/`([\w/]+\.ts)`/g)].map((match) => match[1]);
      for (const module of modules)
        assert.ok(
          files.some(({ file }) => file === module || file.endsWith(`/${module}`)),
          `${name}: ${module} is no module of server/src`,
        );
    }
  });

  it("is ARCHITECTURE.md's table of caches, row for row", () => {
    const architecture = fs.readFileSync(path.join(repoRoot, 'ARCHITECTURE.md'), 'utf8');
    const table = cachesTable();
    assert.ok(architecture.includes(`\n${table}\n`), `ARCHITECTURE.md's table of caches differs from the database; it is:\n${table}`);
  });
});
