import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { SHADOWED_ENTRY_NOTE, UNKNOWN_CATALOG_ENTRY } from '../../../server/src/core/diagnostics/unknownCatalogEntry';
import { ruleIdOf } from '../../../server/src/core/rules';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../../server/src/core/semantics';
import { diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { parseXml } from '../../../server/src/core/xml';
import { esminiBinary, esminiRoads, requireEsmini } from '../../support/esmini';
import { twoCatalogs } from '../../support/twoCatalogs';
import { runBounded } from '../../support/processes';
import { temporaryWorkspace } from '../../support/workspace';

async function analyzed(files: Record<string, string>) {
  const root = temporaryWorkspace(files);
  const semantics = await analyzeDocument(
    diskRef(path.join(root, 'scenario.xosc')),
    parseXml(files['scenario.xosc']),
    new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })),
    false,
  );
  return { root, semantics };
}

describe('diagnostics: unknown-catalog-entry', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNKNOWN_CATALOG_ENTRY.code, 'unknown-catalog-entry');
    assert.equal(UNKNOWN_CATALOG_ENTRY.severity, 'error');
    assert.equal(ruleIdOf('unknown-catalog-entry'), UNKNOWN_CATALOG_ENTRY.rule.qcRule ?? 'modular2simple:unknown-catalog-entry');
    assert.equal(UNKNOWN_CATALOG_ENTRY.isData!({ suggestion: 'car' }), true);
    assert.equal(UNKNOWN_CATALOG_ENTRY.isData!({ suggestion: null }), false);
  });

  it('names the catalog file it looked in, and with no close entry says what to do (a catalog found through the road path may not be the one meant)', async () => {
    const { root, semantics } = await analyzed(twoCatalogs('vehicle.tesla.model3'));
    try {
      const first = path.join(root, 'first', 'VehicleCatalog.xosc');
      const [problem] = semanticProblems(semantics).filter((each) => each.code === 'unknown-catalog-entry');
      assert.equal(problem.message.startsWith(`catalog 'VehicleCatalog' (${first}`), true, problem.message);
      assert.equal(
        problem.hint,
        `name one of its entries, add an entry 'vehicle.tesla.model3' to ${first}, or point the CatalogLocations at the catalog that has it`,
      );
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('two catalog files of one name: the entry is looked up in the first esmini finds, the only one it reads', async () => {
    const { root, semantics } = await analyzed(twoCatalogs('car_red'));
    try {
      const first = path.join(root, 'first', 'VehicleCatalog.xosc');
      const second = path.join(root, 'second', 'VehicleCatalog.xosc');
      const resolution = semantics.catalogs.references[0];
      assert.deepEqual(
        resolution.catalogs.map((file) => file.ref.disk),
        [first, second],
      );
      assert.equal(resolution.entry, undefined);
      const problems = semanticProblems(semantics).filter((problem) => problem.code === 'unknown-catalog-entry');
      assert.equal(problems.length, 1);
      assert.equal(
        problems[0].message,
        `catalog 'VehicleCatalog' (${first}, the first file of that catalog esmini finds, the only one it reads) has no entry named 'car_red'; ${second} has one, which esmini never reads; ${first} has: car_blue`,
      );
      // The entry esmini never reads, named beside the problem.
      assert.deepEqual(
        problems[0].related?.map((related) => [related.source.disk, related.range.start.line, related.message]),
        [
          [
            second,
            fs
              .readFileSync(second, 'utf8')
              .split('\n')
              .findIndex((line) => line.includes('car_red')),
            SHADOWED_ENTRY_NOTE,
          ],
        ],
      );
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('an entry both files have resolves to the one esmini reads (definition and hover go there)', async () => {
    const entryOf = async (files: Record<string, string>) => {
      const { root, semantics } = await analyzed(files);
      try {
        assert.deepEqual(
          semanticProblems(semantics).filter((problem) => problem.code === 'unknown-catalog-entry'),
          [],
        );
        const entry = semantics.catalogs.references[0].entry;
        const text = entry ? fs.readFileSync(entry.file.ref.disk, 'utf8').slice(entry.element.start, entry.element.end) : '';
        return [entry && path.relative(root, entry.file.ref.disk), /maxSpeed="(\d+)"/.exec(text)?.[1]];
      } finally {
        fs.rmSync(root, { recursive: true, force: true });
      }
    };
    assert.deepEqual(await entryOf(twoCatalogs('car_blue')), [path.join('first', 'VehicleCatalog.xosc'), '50']);
    // The first folder's catalog of that name in a file of another name: esmini never finds it (it looks for VehicleCatalog.xosc).
    assert.deepEqual(await entryOf(twoCatalogs('car_blue', 'Vehicles.xosc')), [path.join('second', 'VehicleCatalog.xosc'), '70']);
  });

  it("agrees with esmini: it loads the first folder's catalog and fails on car_red, and runs car_blue", async function () {
    requireEsmini(this);
    const road = fs.readFileSync(path.join(esminiRoads, 'straight_500m.xodr'), 'utf8');
    for (const [entry, fails] of [
      ['car_red', true],
      ['car_blue', false],
    ] as const) {
      const root = temporaryWorkspace({ ...twoCatalogs(entry), 'straight.xodr': road });
      try {
        const run = await runBounded(
          esminiBinary,
          ['--headless', '--osc', 'scenario.xosc', '--fixed_timestep', '0.05', '--disable_log'],
          { cwd: root },
          60_000,
        );
        assert.equal(
          /Couldn't find entry car_red in catalog VehicleCatalog|Failed to look up entry car_red/.test(run.output),
          fails,
          run.output,
        );
        if (!fails) assert.equal(run.code, 0, run.output);
      } finally {
        fs.rmSync(root, { recursive: true, force: true });
      }
    }
  });
});
