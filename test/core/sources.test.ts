import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { Flattener } from '../../server/src/core/flatten';
import { problemData } from '../../server/src/core/problems';
import { childRef, diskRef, readPackageBytes, ScenarioStore, splitScenarioPath } from '../../server/src/core/sources';
import { outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

describe('core: resolving scenarioFileName (SPEC 3)', () => {
  it('splits SCENARIO_PATH on ; and on the platform delimiter', () => {
    assert.deepEqual(splitScenarioPath('/a;/b:/c;;'), ['/a', '/b', '/c']);
    assert.deepEqual(splitScenarioPath(undefined), []);
  });

  it('looks in the package, then SCENARIO_PATH, then parent folders of an unpacked folder', async () => {
    const root = temporaryWorkspace({
      'shared/only-path.xosc': scenario(''),
      'shared/both.xosc': scenario(''),
      'project/both.xosc': scenario(''),
      'project/only-parent.xosc': scenario(''),
      'project/pkg/main.xosc': scenario(''),
      'project/pkg/own.xosc': scenario(''),
    });
    const store = new ScenarioStore({ root: path.join(root, 'project'), scenarioPath: [path.join(root, 'shared')] });
    const from = diskRef(path.join(root, 'project/pkg/main.xosc'));
    const where = async (name: string) => {
      const resolution = await store.resolve(name, from);
      return resolution.kind === 'scenario' ? `${resolution.via}:${path.relative(root, resolution.ref.disk)}` : resolution.kind;
    };
    assert.equal(await where('own.xosc'), 'folder:project/pkg/own.xosc');
    assert.equal(await where('only-path.xosc'), 'scenarioPath:shared/only-path.xosc');
    assert.equal(await where('both.xosc'), 'scenarioPath:shared/both.xosc', 'SCENARIO_PATH comes before parent folders');
    assert.equal(await where('only-parent.xosc'), 'parent:project/only-parent.xosc');
    assert.equal(await where('nowhere.xosc'), 'missing');
    const invalid = await store.resolve('notes.txt', from);
    assert.equal(invalid.kind, 'invalid');
  });

  it('never searches parent folders from inside a .mosc, and a file NAME.mosc wins over a folder NAME/', async () => {
    const zip = new JSZip();
    zip.file('main.xosc', scenario(''));
    const root = temporaryWorkspace({
      'beside.xosc': scenario(''),
      'p.mosc': await zip.generateAsync({ type: 'uint8array' }),
      'p/main.xosc': scenario(''),
    });
    const store = new ScenarioStore({ root, scenarioPath: [] });
    const inside = childRef(diskRef(path.join(root, 'p.mosc')), 'main.xosc');
    assert.equal((await store.resolve('beside.xosc', inside)).kind, 'missing');
    const found = await store.resolve('p.mosc', diskRef(path.join(root, 'beside.xosc')));
    assert.ok(found.kind === 'package' && !found.folder);
  });

  it('keeps each package its own namespace: a nested simple scenario never shadows the outer one', async () => {
    const inner = new JSZip();
    inner.file('main.xosc', scenario(outerGroup('Inner', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }])));
    inner.file('simple.xosc', scenario(simpleGroup('Go').replace('value="10"', 'value="99"')));
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'inner.mosc': await inner.generateAsync({ type: 'uint8array' }),
      'main.xosc': scenario(
        outerGroup('Nested', 'car', [{ file: 'inner.mosc', groups: [{ name: 'Inner.Go' }] }]) +
          outerGroup('Direct', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }]),
      ),
    });
    const text = (await new Flattener(new ScenarioStore({ root, scenarioPath: [] })).flatten(diskRef(path.join(root, 'main.xosc')))).text!;
    const nested = text.slice(text.indexOf('name="Nested.Inner.Go"'), text.indexOf('name="Direct.Go"'));
    const direct = text.slice(text.indexOf('name="Direct.Go"'));
    assert.match(nested, /AbsoluteTargetSpeed value="99"/);
    assert.match(direct, /AbsoluteTargetSpeed value="10"/);
  });

  it('resolves NAME.xosc to the flattened package NAME.mosc, with a warning', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'pkg/main.xosc': scenario(outerGroup('P', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }])),
      'main.xosc': scenario(outerGroup('M', 'car', [{ file: 'pkg.xosc', groups: [{ name: 'P.Go' }] }])),
    });
    const result = await new Flattener(new ScenarioStore({ root, scenarioPath: [] })).flatten(diskRef(path.join(root, 'main.xosc')));
    assert.match(result.text!, /name="M\.P\.Go"/);
    const warning = result.problems.find((p) => p.code === 'xosc-fallback');
    assert.equal(warning?.severity, 'warning');
    assert.equal(warning && problemData(warning, 'xosc-fallback')?.replacement, 'pkg.mosc');
  });
});

describe('core: reading packages safely', () => {
  it('refuses a ZIP bomb at the bound, before it fills memory', async () => {
    const zip = new JSZip();
    zip.file('main.xosc', new Uint8Array(8 * 1024 * 1024), { compression: 'DEFLATE' });
    const bytes = await zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
    assert.ok(bytes.length < 100_000);
    await assert.rejects(
      readPackageBytes(bytes, 'bomb.mosc', { maxEntries: 10, maxEntryBytes: 1024 * 1024, maxTotalBytes: 4 * 1024 * 1024 }),
      /bomb\.mosc\/main\.xosc unpacks to more than 1048576 bytes; it was refused/,
    );
  });

  it('reports a truncated archive as a problem of the file, not a crash', async () => {
    const zip = new JSZip();
    zip.file('main.xosc', scenario(simpleGroup('Go')));
    const bytes = await zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
    const root = temporaryWorkspace({ 'cut.mosc': bytes.slice(0, Math.floor(bytes.length / 2)) });
    const result = await new Flattener(new ScenarioStore({ root, scenarioPath: [] })).flatten(
      childRef(diskRef(path.join(root, 'cut.mosc')), 'main.xosc'),
    );
    assert.equal(result.text, undefined);
    assert.equal(result.problems[0].code, 'bad-package');
    assert.match(result.problems[0].message, /cut\.mosc is not a readable ZIP archive/);
    assert.ok(fs.existsSync(path.join(root, 'cut.mosc')));
  });
});
