import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { resolveScenarioPaths } from '../../client/src/configuration';

describe('client: settings handed to the server per workspace folder', () => {
  it('resolves relative scenarioPath entries against the folder they were set for', () => {
    const second = path.resolve('/work', 'second');
    assert.deepEqual(resolveScenarioPaths({ scenarioPath: ['lib', '../shared', '/abs/lib'], trace: 'off' }, second), {
      scenarioPath: [path.join(second, 'lib'), path.resolve(second, '..', 'shared'), path.resolve('/abs/lib')],
      trace: 'off',
    });
  });

  it('leaves settings alone without a folder or without a scenarioPath list', () => {
    const settings = { scenarioPath: ['lib'] };
    assert.equal(resolveScenarioPaths(settings, undefined), settings);
    assert.deepEqual(resolveScenarioPaths({ trace: 'off' }, '/w'), { trace: 'off' });
    assert.equal(resolveScenarioPaths(null, '/w'), null);
  });
});
