import * as assert from 'node:assert/strict';
import { isWellFormed, parseXml } from '../../server/src/core/xml';
import { mainOf, outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { runBounded } from '../support/hostile';
import { temporaryWorkspace } from '../support/workspace';

describe('cli: text that is not what it claims', function () {
  this.timeout(60_000);

  it('NUL, other control characters and references to non-characters are errors at their position', () => {
    const simple = scenario(simpleGroup('Go'))
      .replace('name="GoManeuver"', 'name="Go\u0001Maneuver"')
      .replace('<Event name="Go"', '<Event name="a&#1;b"')
      .replace('<Action name="Go"', '<Action name="&#xFFFE;"');
    const root = temporaryWorkspace({ 'main.xosc': mainOf('simple.xosc'), 'simple.xosc': simple });
    const run = runBounded(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    const line = (needle: string) => simple.split('\n').findIndex((text) => text.includes(needle)) + 1;
    assert.match(
      run.stderr,
      new RegExp(`simple\\.xosc:${line('GoManeuver') || line('Maneuver name')}:\\d+: error: the character U\\+0001 is not allowed`),
    );
    assert.match(run.stderr, new RegExp(`simple\\.xosc:${line('&#1;')}:\\d+: error: the character reference '&#1;' names U\\+0001`));
    assert.match(run.stderr, /character reference '&#xFFFE;' names U\+FFFE/);
    assert.equal(run.stdout, '');
  });

  it('decodes ISO-8859-1 as declared and UTF-16 with a byte-order mark; the output is UTF-8 and says so', () => {
    const latin = scenario(simpleGroup('Go'))
      .replace('encoding="UTF-8"', 'encoding="ISO-8859-1"')
      .replace('name="GoManeuver"', 'name="Gr\u00fc\u00dfe"');
    const utf16 = Buffer.concat([
      Buffer.from([0xff, 0xfe]),
      Buffer.from(mainOf('latin.xosc').replace('encoding="UTF-8"', 'encoding="UTF-16"'), 'utf16le'),
    ]);
    const root = temporaryWorkspace({ 'main.xosc': utf16, 'latin.xosc': Buffer.from(latin, 'latin1') });
    const run = runBounded(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /^<\?xml version="1.0" encoding="UTF-8"\?>/);
    assert.match(run.stdout, /name="Gr\u00fc\u00dfe"/);
    assert.doesNotMatch(run.stdout, /\uFFFD/);
  });

  it('refuses invalid UTF-8 and an encoding it cannot read, naming them', () => {
    const broken = Buffer.from(scenario(simpleGroup('Go')).replace('name="GoManeuver"', 'name="Gr\u00fc"'), 'latin1');
    const ebcdic = scenario(simpleGroup('Go')).replace('encoding="UTF-8"', 'encoding="EBCDIC-US"');
    const root = temporaryWorkspace({
      'a.xosc': broken,
      'b.xosc': ebcdic,
      'main.xosc': scenario(
        outerGroup('A', 'car', [{ file: 'a.xosc', groups: [{ name: 'Go' }] }]) +
          outerGroup('B', 'car', [{ file: 'b.xosc', groups: [{ name: 'Go' }] }]),
      ),
    });
    const run = runBounded(['check', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /a\.xosc:\d+:1: error: .*byte 0xfc at offset \d+ is not valid UTF-8/);
    assert.match(run.stderr, /encoding="EBCDIC-US", which cannot be read/);
    assert.doesNotMatch(run.stderr, /\uFFFD/);
  });

  it('an internal DTD entity used inside an imported group is expanded in the copy', () => {
    const simple = scenario(simpleGroup('Go'))
      .replace('<OpenSCENARIO>', '<!DOCTYPE OpenSCENARIO [\n  <!ENTITY speed "12.5">\n  <!ENTITY who "car &amp; co">\n]>\n<OpenSCENARIO>')
      .replace('z="0"', 'z="&speed;"')
      .replace(
        '<Event name="Go" priority="overwrite">',
        '<Event name="Go" priority="overwrite">\n              <!-- &who; -->\n              <Note>&who; at &speed;</Note>',
      );
    const root = temporaryWorkspace({ 'main.xosc': mainOf('simple.xosc'), 'simple.xosc': simple });
    const run = runBounded(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.ok(isWellFormed(parseXml(run.stdout)), 'the output is well-formed');
    assert.match(run.stdout, /z="12\.5"/);
    assert.match(run.stdout, /<Note>car &amp; co at 12\.5<\/Note>/);
  });
});
