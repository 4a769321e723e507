import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { fileNameProblem, freeScenarioName, scenarioFileName } from '../../client/src/naming';

describe('client: the file name New Modular Scenario proposes and accepts', () => {
  const folder = path.resolve('/work', 'scenarios');
  const existing =
    (...names: string[]) =>
    (file: string) =>
      names.some((name) => path.join(folder, name) === file);

  it('proposes main.xosc, or the first main-N.xosc that is free', () => {
    assert.equal(freeScenarioName(folder, existing()), 'main.xosc');
    assert.equal(freeScenarioName(folder, existing('main.xosc')), 'main-2.xosc');
    assert.equal(freeScenarioName(folder, existing('main.xosc', 'main-2.xosc')), 'main-3.xosc');
  });

  it('refuses a name that exists, has no .xosc ending or names folders', () => {
    assert.equal(fileNameProblem(folder, 'cut-in.xosc', existing('main.xosc')), undefined);
    assert.match(fileNameProblem(folder, 'main.xosc', existing('main.xosc')) ?? '', /exists already/);
    assert.match(fileNameProblem(folder, 'main.xml', existing()) ?? '', /end in \.xosc/);
    assert.match(fileNameProblem(folder, '.xosc', existing()) ?? '', /end in \.xosc/);
    assert.match(fileNameProblem(folder, '../main.xosc', existing()) ?? '', /without folders/);
  });

  it('takes a name typed without an extension as NAME.xosc (it said "The name must end in .xosc")', () => {
    assert.equal(scenarioFileName(' encounter '), 'encounter.xosc');
    assert.equal(fileNameProblem(folder, 'encounter', existing()), undefined);
    assert.match(fileNameProblem(folder, 'main', existing('main.xosc')) ?? '', /^main\.xosc exists already/);
    assert.equal(scenarioFileName('cut-in.xosc'), 'cut-in.xosc');
    assert.match(fileNameProblem(folder, 'main.xml', existing()) ?? '', /end in \.xosc/);
    assert.match(fileNameProblem(folder, '.hidden', existing()) ?? '', /end in \.xosc/);
    assert.match(fileNameProblem(folder, 'compose/encounter', existing()) ?? '', /without folders/);
  });
});
