import * as esbuild from 'esbuild';
import { createRequire } from 'node:module';
import path from 'node:path';
await esbuild.build({ stdin: { contents: `export * from './server/src/core/semantics'; export * from './server/src/core/semantics/esminiValues'; export { parseXml } from './server/src/core/xml';`, resolveDir: '/work/wt/values', loader: 'ts' }, bundle: true, platform: 'node', format: 'cjs', outfile: '/tmp/values-prof/sem2.cjs', logLevel: 'warning' });
const { parameterScenario } = await import(path.join('/work/wt/values', 'bench/parameterScenario.mjs'));
const core = createRequire(import.meta.url)('/tmp/values-prof/sem2.cjs');
const doc = core.parseXml(parameterScenario());
const model = core.semanticModelOf(doc);
const time = (label, f) => { const t = performance.now(); for (let i = 0; i < 30; i++) f(); console.log(label, ((performance.now() - t) / 30).toFixed(2)); };
for (let k = 0; k < 2; k++) {
time('declarations', () => { const e = new core.Evaluator(model); for (const d of model.declarations) e.declarationValue(d); });
time('sites', () => { const e = new core.Evaluator(model); for (const s of model.sites) e.evaluateSite(s); });
time('esmini only', () => { const e = new core.Evaluator(model); for (const s of model.sites) e.esminiSiteText(s); });
time('esminiExpression', () => { for (const s of model.sites) if (s.form.kind === 'expression') core.esminiExpression(s.attribute.value.slice(2, -1), () => ({ ok: true, text: '12', rules: [] })); });
time('evaluateTree', () => { for (const s of model.sites) if (s.form.kind === 'expression') core.evaluateTree(s.form.expression.tree, () => ({ value: 12, type: 'double' })); });
}
