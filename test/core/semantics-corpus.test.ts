import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { formatProblem } from '../../server/src/core/problems';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { corpusFiles, expectedCorpusFindings, GENUINELY_WRONG, openscenarioDir, SEMANTIC_CODES } from '../support/openscenarioCorpus';

describe('semantics on the real OpenSCENARIO corpus (../shared/corpus/openscenario)', function () {
  this.timeout(120_000);

  before(function () {
    if (!fs.existsSync(openscenarioDir)) {
      console.log(`    (skipped: ${openscenarioDir} is absent)`);
      this.skip();
    }
  });

  it('reports no false error or warning on any of the 101 files, and resolves their catalogs', async () => {
    const files = corpusFiles();
    assert.equal(files.length, 101);
    // Catalogs are found as esmini and CARLA are told to find them: esmini with --path per catalog folder, CARLA beside the scenario.
    const esmini = new Flattener(new ScenarioStore({ scenarioPath: [path.join(openscenarioDir, 'esmini', 'Catalogs')] }));
    const carla = new Flattener(new ScenarioStore({ scenarioPath: [path.join(openscenarioDir, 'scenario_runner')] }));
    const found: Record<string, string[]> = {};
    const shown: string[] = [];
    let references = 0;
    let resolved = 0;
    let uses = 0;
    let expressions = 0;
    for (const file of files) {
      const relative = path.relative(openscenarioDir, file);
      const analysis = await (relative.startsWith('esmini') ? esmini : carla).analyze(diskRef(file));
      const semantics = analysis.source.semantics;
      assert.ok(semantics, relative);
      references += semantics.catalogs.references.length;
      resolved += semantics.catalogs.references.filter((reference) => reference.entry).length;
      uses += semantics.model.uses.filter((use) => use.declaration).length;
      expressions += semantics.model.sites.filter((site) => site.form.kind === 'expression').length;
      for (const problem of analysis.problems) {
        if (!SEMANTIC_CODES.has(problem.code) || (problem.severity !== 'error' && problem.severity !== 'warning')) continue;
        (found[relative] ??= []).push(`${problem.range.start.line + 1}:${problem.code}`);
        shown.push(formatProblem(problem, openscenarioDir));
      }
    }
    const sorted = (lists: Record<string, string[]>) =>
      Object.fromEntries(Object.entries(lists).map(([file, problems]) => [file, [...problems].sort()]));
    const expected = expectedCorpusFindings();
    assert.deepEqual(sorted(found), sorted(expected), shown.join('\n'));
    // The checks had something to check: every $name resolved, expressions evaluated, catalog entries found.
    assert.ok(uses > 400, `${uses} resolved uses`);
    assert.ok(expressions > 60, `${expressions} expressions`);
    // Unresolved: car_walk's 12, and the trailer that VehicleCatalog.xosc takes from a catalog only its users locate.
    assert.ok(references > 150 && references - resolved === 13, `${resolved} of ${references} catalog references resolved`);
  });

  it("reads esmini's scenarios as esmini does (simulator esmini, SPEC 12): no error but in the genuinely wrong files, and none in cut-in, cut-in_environment and traffic_lights", async () => {
    const files = corpusFiles().filter((file) => path.relative(openscenarioDir, file).startsWith('esmini'));
    const esmini = new Flattener(new ScenarioStore({ scenarioPath: [path.join(openscenarioDir, 'esmini', 'Catalogs')] }), 'esmini');
    const errors: Record<string, string[]> = {};
    const shown: string[] = [];
    for (const file of files) {
      const relative = path.relative(openscenarioDir, file);
      const analysis = await esmini.analyze(diskRef(file));
      for (const problem of analysis.problems) {
        if (!SEMANTIC_CODES.has(problem.code) || problem.severity !== 'error') continue;
        (errors[relative] ??= []).push(`${problem.range.start.line + 1}:${problem.code}`);
        shown.push(formatProblem(problem, openscenarioDir));
      }
    }
    // The errors among GENUINELY_WRONG (the rest there are warnings): a catalog esmini does not ship. The pressure out of
    // range is a warning: esmini clamps it and runs; so is the double declared 'time', whose text esmini puts where it is used (SPEC 12).
    const wrongErrors: Record<string, string[]> = {
      'esmini/car_walk.xosc': GENUINELY_WRONG['esmini/car_walk.xosc'].problems,
    };
    assert.deepEqual(errors, wrongErrors, shown.join('\n'));
    for (const file of ['cut-in.xosc', 'cut-in_environment.xosc', 'traffic_lights.xosc']) assert.ok(!errors[`esmini/${file}`], file);
  });
});
