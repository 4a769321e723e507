// Semantic model benchmark (printed figures): a scenario with 1,000 parameters and 1,000 expressions;
// building the model, running every check, and the per-offset queries the editor features make.
import * as esbuild from 'esbuild';
import { mkdtempSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parameterScenario } from './parameterScenario.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const runs = Number(process.env.BENCH_RUNS ?? 15) * 2;
const work = mkdtempSync(path.join(tmpdir(), 'm2s-bench-semantics-'));
const bundle = path.join(work, 'semantics.cjs');
await esbuild.build({
  stdin: {
    contents: `export * from './server/src/core/semantics'; export { parseXml } from './server/src/core/xml';`,
    resolveDir: root,
    loader: 'ts',
  },
  bundle: true,
  platform: 'node',
  format: 'cjs',
  outfile: bundle,
  logLevel: 'warning',
});
/** @type {typeof import('../server/src/core/semantics') & Pick<typeof import('../server/src/core/xml'), 'parseXml'>} */
const core = createRequire(import.meta.url)(bundle);
rmSync(work, { recursive: true, force: true });

/**
 * @template T
 * @param {() => T} action
 */
function time(action) {
  const started = process.hrtime.bigint();
  const result = action();
  return { ms: Number(process.hrtime.bigint() - started) / 1e6, result };
}

/** @param {number[]} samples */
function summary(samples) {
  const sorted = [...samples].sort((a, b) => a - b);
  return { median: sorted[Math.floor(sorted.length / 2)], p95: sorted[Math.min(sorted.length - 1, Math.ceil(sorted.length * 0.95) - 1)] };
}

const text = parameterScenario();
const emptyCatalogs = { locations: [], references: [], files: [] };
const ref = { disk: path.join(root, 'bench.xosc'), entries: [] };
/** @type {number[]} */
const parse = [];
/** @type {number[]} */
const build = [];
/** @type {number[]} */
const check = [];
let last;
for (let run = 0; run < runs; run++) {
  const parsed = time(() => core.parseXml(text));
  parse.push(parsed.ms);
  const built = time(() => core.buildSemanticModel(parsed.result));
  build.push(built.ms);
  const model = built.result;
  const checked = time(() => core.runChecks({ ref, model, evaluator: new core.Evaluator(model), catalogs: emptyCatalogs, modular: false }));
  check.push(checked.ms);
  last = { model, findings: checked.result };
}
if (!last) throw new Error('BENCH_RUNS is 0: nothing was measured');
if (last.model.declarations.length !== 1000 || last.model.sites.filter((site) => site.form.kind === 'expression').length !== 1500)
  throw new Error('the generated scenario is not what the benchmark states');
if (last.findings.some((finding) => finding.severity === 'error')) throw new Error(`unexpected errors: ${last.findings[0].message}`);

// Queries at offsets spread over the file, on one model (as the editor asks them between edits).
const semantics = { ref, model: last.model, evaluator: new core.Evaluator(last.model), catalogs: emptyCatalogs, modular: false };
const offsets = last.model.uses.filter((_, index) => index % 10 === 0).map((use) => use.start + 1);
/** @param {(semantics: Parameters<typeof core.declarationAt>[0], offset: number) => unknown} fn */
const query = (fn) => summary(offsets.map((offset) => time(() => fn(semantics, offset)).ms));
const definition = query(core.declarationAt);
const value = query(core.valueAt);
const inScope = query(core.parametersInScopeAt);
const references = summary(
  last.model.declarations.slice(0, 100).map((declaration) => time(() => core.referencesOf(semantics, declaration)).ms),
);

/** @param {number} n */
const fmt = (n) => n.toFixed(2).padStart(8);
console.log(
  `semantic model benchmark: ${(text.length / 1024).toFixed(0)} KB, 1,000 parameters, 1,000 attributes with expressions (${runs} runs)`,
);
console.log('                                           median ms    p95 ms');
console.log(`  parse XML                                 ${fmt(summary(parse).median)}  ${fmt(summary(parse).p95)}`);
console.log(`  build the semantic model                  ${fmt(summary(build).median)}  ${fmt(summary(build).p95)}`);
console.log(`  run every check (evaluates all values)    ${fmt(summary(check).median)}  ${fmt(summary(check).p95)}`);
console.log(`  declarationAt (${offsets.length} offsets)             ${fmt(definition.median)}  ${fmt(definition.p95)}`);
console.log(`  valueAt, evaluated (${offsets.length} offsets)        ${fmt(value.median)}  ${fmt(value.p95)}`);
console.log(`  parametersInScopeAt with values           ${fmt(inScope.median)}  ${fmt(inScope.p95)}`);
console.log(`  referencesOf (100 declarations)           ${fmt(references.median)}  ${fmt(references.p95)}`);
const total = summary(parse.map((ms, index) => ms + build[index] + check[index]));
// From scratch, as on opening a file or after an edit of a name, a type or a reference; an edit inside one value
// carries the model over instead (bench/editorFeatures.mjs times that, over the language server).
console.log(
  `  parse + model + checks from scratch: ${fmt(total.median)}  ${fmt(total.p95)}   (opening, or an edit of a name, type or reference)`,
);
