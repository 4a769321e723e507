import * as assert from 'node:assert/strict';
import { attribute, elementAt, escapeAttributeValue, isWellFormed, parseXml } from '../../server/src/core/xml';

describe('core: XML parser with positions', () => {
  it('records offsets of elements, attribute names and values', () => {
    const text = '<?xml version="1.0"?>\n<Root>\n  <Child a="1" b=\'two\'/>\n</Root>\n';
    const document = parseXml(text);
    assert.ok(isWellFormed(document));
    const child = document.root?.children[0];
    assert.equal(child?.name, 'Child');
    const b = child && attribute(child, 'b');
    assert.equal(b?.value, 'two');
    assert.equal(text.slice(b!.nameStart, b!.nameEnd), 'b');
    assert.equal(text.slice(b!.valueStart, b!.valueEnd), 'two');
    assert.equal(b?.quote, "'");
    assert.deepEqual(document.lines.positionAt(child!.start), { line: 2, character: 2 });
    assert.equal(text.slice(document.root!.start, document.root!.end), '<Root>\n  <Child a="1" b=\'two\'/>\n</Root>');
    assert.equal(elementAt(document, b!.valueStart)?.name, 'Child');
  });

  it('decodes references in values and escapes them back', () => {
    const document = parseXml('<R v="a &lt;&amp;&quot; &#233;&#x4E2D;"/>');
    assert.equal(document.root?.attributes[0].value, 'a <&" é中');
    assert.equal(escapeAttributeValue('<&">\''), "&lt;&amp;&quot;&gt;'");
    assert.equal(escapeAttributeValue("it's", "'"), 'it&apos;s');
  });

  it('reports well-formedness errors with line and column', () => {
    const text = '<Root>\n  <A>\n  </B>\n</Root>';
    const document = parseXml(text);
    assert.ok(!isWellFormed(document));
    const problem = document.problems.find((p) => /no matching start tag/.test(p.message));
    assert.ok(problem, JSON.stringify(document.problems));
    assert.deepEqual(document.lines.positionAt(problem.start), { line: 2, character: 2 });
    const unclosed = parseXml('<Root>\n  <A x="1">');
    assert.ok(unclosed.problems.some((p) => /<A> is not closed/.test(p.message)));
    assert.ok(unclosed.problems.some((p) => /<Root> is not closed/.test(p.message)));
  });

  it('accepts a UTF-8 byte-order mark', () => {
    const document = parseXml('\uFEFF<?xml version="1.0" encoding="UTF-8"?><R/>');
    assert.ok(isWellFormed(document), JSON.stringify(document.problems));
  });

  it('never resolves an external entity', () => {
    const text = '<?xml version="1.0"?>\n<!DOCTYPE R [ <!ENTITY secret SYSTEM "file:///etc/passwd"> ]>\n<R a="&secret;">&secret;</R>';
    const document = parseXml(text);
    assert.equal(document.root?.attributes[0].value, '');
    assert.ok(document.problems.some((p) => p.severity === 'error' && /external entity '&secret;' is never resolved/.test(p.message)));
  });

  it('bounds internal entity expansion (billion laughs)', () => {
    let subset = '<!ENTITY a0 "lol">';
    for (let i = 1; i <= 9; i++) subset += `<!ENTITY a${i} "${`&a${i - 1};`.repeat(10)}">`;
    const started = process.hrtime.bigint();
    const document = parseXml(`<!DOCTYPE R [${subset}]><R v="&a9;"/>`, { maxEntityExpansion: 100_000 });
    assert.ok(Number(process.hrtime.bigint() - started) / 1e6 < 5000);
    assert.ok(document.root!.attributes[0].value.length <= 100_000);
    assert.ok(document.problems.some((p) => /expansion/.test(p.message)));
  });

  it('recovers from a value being typed without swallowing the rest of the file', () => {
    const text = '<R>\n  <P key="Abs\n  <Q name="x"/>\n</R>';
    const document = parseXml(text);
    assert.ok(!isWellFormed(document));
    assert.deepEqual(
      document.root?.children.map((c) => c.name),
      ['P', 'Q'],
    );
    assert.equal(attribute(document.root!.children[1], 'name')?.value, 'x');
  });

  it('stops at a nesting bound instead of overflowing the stack', () => {
    const depth = 5000;
    const document = parseXml('<a>'.repeat(depth) + '</a>'.repeat(depth), { maxDepth: 1000 });
    assert.ok(document.problems.some((p) => /nest deeper/.test(p.message)));
  });

  it('reports binary garbage instead of throwing', () => {
    const garbage = String.fromCharCode(...Array.from({ length: 2000 }, (_, i) => (i * 7919) % 256));
    const document = parseXml(garbage);
    assert.ok(document.problems.length > 0);
  });
});
