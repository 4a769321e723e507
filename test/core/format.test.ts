import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import fc from 'fast-check';
import JSZip from 'jszip';
import { firstDifference } from '../../server/src/core/equivalence';
import { applyEdits, detectIndentation, FormatOptions, formatXml } from '../../server/src/core/format';
import { LineIndex } from '../../server/src/core/text';
import { sharedDir } from '../support/paths';

const TWO: FormatOptions = { tabSize: 2, insertSpaces: true, maxLineWidth: 120 };

function format(text: string, options: FormatOptions = TWO): string {
  const result = formatXml(text, options);
  if (!result.ok) throw new Error(result.message);
  return result.text;
}

describe('formatter (core)', () => {
  it('indents nested elements by the given unit and normalizes white space inside tags', () => {
    const input = '<A>\n<B   x = "1"  y=\'2\' />\n      <C></C >\n</A>';
    assert.equal(format(input), '<A>\n  <B x="1" y=\'2\'/>\n  <C></C>\n</A>\n');
    assert.equal(format(input, { tabSize: 4, insertSpaces: false, maxLineWidth: 120 }), '<A>\n\t<B x="1" y=\'2\'/>\n\t<C></C>\n</A>\n');
    assert.equal(format(input, { tabSize: 4, insertSpaces: true, maxLineWidth: 120 }), '<A>\n    <B x="1" y=\'2\'/>\n    <C></C>\n</A>\n');
  });

  it('keeps the XML declaration, processing instructions, DOCTYPE and comments, each on its own line', () => {
    const input =
      '<?xml version="1.0" encoding="UTF-8"?><!DOCTYPE A [ <!ENTITY e "v"> ]><!--  top  comment  --><A><?pi  some  data ?><!--inner--><B/></A><!--end-->';
    assert.equal(
      format(input),
      '<?xml version="1.0" encoding="UTF-8"?>\n<!DOCTYPE A [ <!ENTITY e "v"> ]>\n<!--  top  comment  -->\n<A>\n  <?pi  some  data ?> <!--inner-->\n  <B/>\n</A>\n<!--end-->\n',
    );
  });

  it('keeps a multi-line comment byte for byte and a comment that followed a tag on its line', () => {
    const input = '<A>\n<B/>   <!-- about B -->\n      <!--\n   two\n        lines\n  -->\n<C/></A>';
    assert.equal(format(input), '<A>\n  <B/> <!-- about B -->\n  <!--\n   two\n        lines\n  -->\n  <C/>\n</A>\n');
  });

  it('collapses several blank lines between siblings to one and drops them after a start tag or before an end tag', () => {
    const input = '<A>\n\n\n<B/>\n<C/>\n\n\n\n<D/>\n\n</A>\n\n\n';
    assert.equal(format(input), '<A>\n  <B/>\n  <C/>\n\n  <D/>\n</A>\n');
  });

  it('keeps the content of an element holding text or CDATA as written (mixed content)', () => {
    const input =
      '<A>\n<Text   a="1">  two  spaces\n     kept <b>bold</b>  </Text>\n<Data><![CDATA[ <x>  ]]></Data>\n<Space xml:space="preserve">\n   <Kept/>\n</Space></A>';
    assert.equal(
      format(input),
      '<A>\n  <Text a="1">  two  spaces\n     kept <b>bold</b>  </Text>\n  <Data><![CDATA[ <x>  ]]></Data>\n  <Space xml:space="preserve">\n   <Kept/>\n</Space>\n</A>\n',
    );
  });

  it('puts attributes one per line past the width, counting the indentation, and never reorders or re-quotes them', () => {
    const attributes = 'zeta="1" alpha=\'a &amp; b\' middle="$param" expr="${$x + 1}"';
    const input = `<A><LongElementName ${attributes}/><Short a="1"/></A>`;
    const narrow = format(input, { tabSize: 2, insertSpaces: true, maxLineWidth: 40 });
    assert.equal(
      narrow,
      '<A>\n  <LongElementName\n    zeta="1"\n    alpha=\'a &amp; b\'\n    middle="$param"\n    expr="${$x + 1}"/>\n  <Short a="1"/>\n</A>\n',
    );
    const wide = format(input, { tabSize: 2, insertSpaces: true, maxLineWidth: 120 });
    assert.ok(wide.includes(`  <LongElementName ${attributes}/>`));
    // The line of the wide form is 2 + 86 columns: exactly at the width stays on one line, one less wraps.
    const lineLength = `  <LongElementName ${attributes}/>`.length;
    assert.ok(format(input, { tabSize: 2, insertSpaces: true, maxLineWidth: lineLength }).includes(`<LongElementName ${attributes}/>`));
    assert.ok(
      !format(input, { tabSize: 2, insertSpaces: true, maxLineWidth: lineLength - 1 }).includes(`<LongElementName ${attributes}/>`),
    );
    // A tab counts as tabSize columns when the width is measured.
    const tabbed = format(input, { tabSize: 8, insertSpaces: false, maxLineWidth: lineLength + 5 });
    assert.ok(!tabbed.includes(`<LongElementName ${attributes}/>`));
  });

  it('keeps a single long attribute on the line of its element', () => {
    const value = 'x'.repeat(200);
    assert.equal(format(`<A><B v="${value}"/></A>`), `<A>\n  <B v="${value}"/>\n</A>\n`);
  });

  it('keeps attribute values with line breaks, tabs and references byte for byte', () => {
    const input = '<A><B v="line one\n   line two" w="a\tb" e="&#10;&lt;"/></A>';
    const output = format(input);
    assert.ok(output.includes('v="line one\n   line two"'));
    assert.ok(output.includes('w="a\tb"'));
    assert.ok(output.includes('e="&#10;&lt;"'));
    assert.equal(firstDifference(input, output), undefined);
  });

  it('keeps CRLF line ends and a byte-order mark', () => {
    const input = '\uFEFF<?xml version="1.0"?>\r\n<A>\r\n<B/>\r\n</A>';
    assert.equal(format(input), '\uFEFF<?xml version="1.0"?>\r\n<A>\r\n  <B/>\r\n</A>\r\n');
  });

  it("gives the line breaks wanted before the first one in the file (gaps held until then) the file's line end", () => {
    assert.equal(format('<A><B/><C/>\r\n</A>'), '<A>\r\n  <B/>\r\n  <C/>\r\n</A>\r\n');
    assert.equal(format('<A><B/><C/>\n</A>'), '<A>\n  <B/>\n  <C/>\n</A>\n');
    // No line break between markup: the first one of the file decides, here inside a comment (kept on its line).
    assert.equal(format('<A><B/><!-- a\r\nb --></A>'), '<A>\r\n  <B/> <!-- a\r\nb -->\r\n</A>\r\n');
  });

  it('places the edits of a format on lines exactly as a search per offset does, LF, CRLF and CR alike', () => {
    for (const input of [
      '<A>\n<B   x = "1"/>\n\n\n<C>\n<D/></C></A>',
      '<A>\r\n<B/>\r\n<C>\r\n\r\n<D/></C></A>',
      '<A>\r<B/>\r\r<C><D/></C></A>',
    ]) {
      const result = formatXml(input, { tabSize: 4, insertSpaces: false, maxLineWidth: 10 });
      assert.ok(result.ok && result.edits.length > 3, input);
      const lines = new LineIndex(input);
      assert.deepEqual(
        lines.rangesInOrder(result.edits),
        result.edits.map((edit) => lines.range(edit.start, edit.end)),
      );
      // Spans out of order still get their own places.
      const reversed = [...result.edits].reverse();
      assert.deepEqual(
        lines.rangesInOrder(reversed),
        reversed.map((edit) => lines.range(edit.start, edit.end)),
      );
    }
  });

  it('is idempotent and changes nothing in an already formatted document (no edits)', () => {
    const input = '<?xml version="1.0"?>\n<!-- c -->\n<A>\n  <B x="1"/>\n\n  <C>\n    <D/>\n  </C>\n</A>\n';
    const result = formatXml(input, TWO);
    assert.ok(result.ok);
    assert.deepEqual(result.edits, []);
  });

  it('refuses malformed XML with a message naming the line, and returns no edits', () => {
    for (const input of ['<A><B></A>', '<A x="1></A>', '<A>', '', 'text only', '<A/><B/>', '<A><!-- open </A>']) {
      const result = formatXml(input, TWO);
      assert.equal(result.ok, false, JSON.stringify(input));
      if (!result.ok) assert.match(result.message, /not formatted: .*line \d+/);
    }
  });

  it('computes small edits (white space only) rather than one whole replacement', () => {
    const input = '<A>\n<B/>\n  <C/>\n</A>\n';
    const result = formatXml(input, TWO);
    assert.ok(result.ok);
    assert.deepEqual(result.edits, [{ start: 3, end: 4, newText: '\n  ' }]);
    for (const edit of result.edits) assert.match(input.slice(edit.start, edit.end), /^\s*$/);
  });

  it('formats only the selected lines, with the indentation of their place in the document', () => {
    const input = '<A>\n<B>\n<C/>\n<D/>\n</B>\n<E/>\n</A>\n';
    const start = input.indexOf('<C/>');
    const end = input.indexOf('<D/>') + 2;
    const result = formatXml(input, TWO, { start, end });
    assert.ok(result.ok);
    assert.equal(result.text, '<A>\n<B>\n    <C/>\n    <D/>\n</B>\n<E/>\n</A>\n');
    assert.equal(applyEdits(input, result.edits), result.text);
  });

  it('detects the indentation a file uses', () => {
    assert.deepEqual(detectIndentation('<A>\n    <B/>\n</A>'), { tabSize: 4, insertSpaces: true });
    assert.deepEqual(detectIndentation('<A>\n\t<B/>\n</A>'), { tabSize: 4, insertSpaces: false });
    assert.deepEqual(detectIndentation('<A><B/></A>'), { tabSize: 2, insertSpaces: true });
  });
});

describe('formatter on every corpus file', function () {
  const corpus = path.join(sharedDir, 'corpus');
  const files: { name: string; text: string }[] = [];
  before(async function () {
    if (!fs.existsSync(corpus)) {
      console.log(`    (skipped: ${corpus} is absent)`);
      this.skip();
    }
    const walk = (folder: string) => {
      for (const entry of fs.readdirSync(folder, { withFileTypes: true })) {
        const full = path.join(folder, entry.name);
        if (entry.isDirectory()) walk(full);
        else if (/\.xosc$/i.test(entry.name)) files.push({ name: full, text: fs.readFileSync(full, 'utf8') });
        else if (/\.mosc$/i.test(entry.name)) packages.push(full);
      }
    };
    const packages: string[] = [];
    walk(corpus);
    // The scenarios inside packages are formatted as well: an editor opens them as mosc: documents.
    for (const file of packages) {
      const zip = await JSZip.loadAsync(fs.readFileSync(file));
      for (const entry of Object.values(zip.files)) {
        if (!entry.dir && /\.xosc$/i.test(entry.name)) files.push({ name: `${file}/${entry.name}`, text: await entry.async('string') });
      }
    }
  });

  const settings: [string, (text: string) => FormatOptions][] = [
    ['the indentation the file uses, width 120', (text) => ({ ...detectIndentation(text), maxLineWidth: 120 })],
    ['tabs, width 40 (attributes wrapped)', () => ({ tabSize: 4, insertSpaces: false, maxLineWidth: 40 })],
  ];
  for (const [name, optionsFor] of settings) {
    it(`formats twice as once and keeps each file equivalent (${name})`, () => {
      assert.ok(files.length >= 200, `expected the whole corpus, found ${files.length} .xosc files`);
      let changed = 0;
      for (const { name: file, text } of files) {
        const options = optionsFor(text);
        const once = formatXml(text, options);
        assert.ok(once.ok, `${file}: ${!once.ok && once.message}`);
        const twice = formatXml(once.text, options);
        assert.ok(twice.ok && twice.text === once.text && twice.edits.length === 0, `${file}: a second pass changed the text`);
        assert.equal(firstDifference(text, once.text), undefined, file);
        if (once.text !== text) changed++;
      }
      assert.ok(changed > 0, 'no corpus file changed: the test would not show anything');
    });
  }
});

describe('formatter on generated documents (property)', () => {
  // Random well-formed documents: elements, attributes with any characters, comments, text, CDATA,
  // processing instructions, and random white space between all of them.
  const space = fc.constantFrom('', ' ', '\n', '\n\n\n', '\t', '  \r\n  ', '\n    ');
  const name = fc.constantFrom('A', 'Event', 'x:y', 'Long_Name-1', 'ScenarioObject');
  const escape = (raw: string) => raw.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/"/g, '&quot;');
  const attributes = fc.uniqueArray(
    fc.tuple(fc.constantFrom('a', 'name', 'value', 'xml:space', 'b-c'), fc.string({ maxLength: 12 }), space),
    { selector: ([key]) => key, maxLength: 5 },
  );
  const comment = fc
    .string({ maxLength: 10 })
    .filter((body) => !body.includes('--') && !body.endsWith('-'))
    .map((body) => `<!--${body}-->`);
  const text = fc.string({ minLength: 1, maxLength: 10 }).map((raw) => escape(raw).replace(/]]>/g, ']]&gt;'));
  const cdata = fc
    .string({ maxLength: 10 })
    .filter((body) => !body.includes(']]>'))
    .map((body) => `<![CDATA[${body}]]>`);
  const pi = fc.constantFrom('<?target some data?>', '<?pi?>');
  const { element } = fc.letrec<{ element: string; node: string }>((tie) => ({
    element: fc
      .tuple(name, attributes, space, fc.boolean(), fc.array(fc.tuple(space, tie('node')), { maxLength: 4 }), space)
      .map(([tag, attrs, inner, selfClosing, children, end]) => {
        const open = `<${tag}${attrs.map(([key, value, gap]) => ` ${gap}${key}${gap}=${gap}"${escape(value)}"`).join('')}${inner}`;
        if (selfClosing && children.length === 0) return `${open}/>`;
        return `${open}>${children.map(([gap, child]) => gap + child).join('')}${end}</${tag}>`;
      }),
    // At the depth limit oneof takes its first choice, so a leaf comes first.
    node: fc.oneof({ maxDepth: 4, withCrossShrink: true }, comment, text, cdata, pi, tie('element'), tie('element')),
  }));
  const documentText = fc
    .tuple(fc.boolean(), space, fc.option(comment), space, element, space)
    .map(([declaration, a, before, b, root, c]) => `${declaration ? '<?xml version="1.0"?>' : ''}${a}${before ?? ''}${b}${root}${c}`);
  const optionsArbitrary = fc.record({
    tabSize: fc.integer({ min: 1, max: 8 }),
    insertSpaces: fc.boolean(),
    maxLineWidth: fc.integer({ min: 10, max: 120 }),
  });

  it('changes only white space, keeps the document equivalent, and a second pass changes nothing', () => {
    fc.assert(
      fc.property(documentText, optionsArbitrary, (input, options) => {
        const once = formatXml(input, options);
        assert.ok(once.ok, `${input}\n${!once.ok && once.message}`);
        assert.equal(once.text.replace(/\s+/g, ''), input.replace(/\s+/g, ''));
        assert.equal(firstDifference(input, once.text), undefined);
        const twice = formatXml(once.text, options);
        assert.ok(twice.ok);
        assert.equal(twice.text, once.text);
      }),
      { numRuns: 300 },
    );
  });

  it('never formats a mutilated document into something else: it refuses or keeps the same non-blank text', () => {
    fc.assert(
      fc.property(documentText, fc.nat(), fc.nat({ max: 5 }), optionsArbitrary, (input, at, length, options) => {
        const start = input.length === 0 ? 0 : at % input.length;
        const broken = input.slice(0, start) + input.slice(start + length);
        const result = formatXml(broken, options);
        if (result.ok) assert.equal(result.text.replace(/\s+/g, ''), broken.replace(/\s+/g, ''));
      }),
      { numRuns: 300 },
    );
  });
});
