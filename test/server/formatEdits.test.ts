import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { splitFormatReply, whitespaceEdits } from '../../common/src/whitespaceEdits';
import { detectIndentation, editorEdits, FormatOptions, formatXml, SEPARATE_EDITS_UP_TO } from '../../server/src/core/format';
import { formattingEdits } from '../../server/src/features/formatting';
import { repoRoot, sharedDir } from '../support/paths';
import { applyTextEditsAsSpecified } from '../support/textEdits';

/** A scenario of `groups` maneuver groups written at column 0, several tags to a line: many edits when formatted. */
function messy(groups: number): string {
  const parts = ['<?xml version="1.0" encoding="UTF-8"?>', '<OpenSCENARIO>', '<Storyboard>', '<Story name="S">', '<Act name="A">'];
  for (let group = 0; group < groups; group++) {
    parts.push(
      `<ManeuverGroup name="G${group}" maximumExecutionCount="1">`,
      '<Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>',
      `<!-- maneuver ${group} -->`,
      '',
      '',
      `<Maneuver name="M${group}"><Event name="E${group}" priority="overwrite"/></Maneuver>`,
      '</ManeuverGroup>',
    );
  }
  parts.push('</Act>', '</Story>', '</Storyboard>', '</OpenSCENARIO>', '');
  return parts.join('\n');
}

function xoscFiles(folder: string, into: string[] = []): string[] {
  for (const entry of fs.readdirSync(folder, { withFileTypes: true })) {
    const full = path.join(folder, entry.name);
    if (entry.isDirectory()) xoscFiles(full, into);
    else if (/\.xosc$/i.test(entry.name)) into.push(full);
  }
  return into;
}

const lineEnds: [string, (text: string) => string][] = [
  ['LF', (text) => text.replace(/\r\n?/g, '\n')],
  ['CRLF', (text) => text.replace(/\r\n?/g, '\n').replace(/\n/g, '\r\n')],
  ['CR', (text) => text.replace(/\r\n?/g, '\n').replace(/\n/g, '\r')],
];

/**
 * The edits an editor gets for `text` (whole, or the lines of `range`), applied as LSP says, read the formatter's
 * text; the formatter's text gets no edits; and one edit (past the limit) splits back into the separate edits.
 */
function checkReply(name: string, text: string, options: FormatOptions, range?: { start: number; end: number }): number {
  const editor = { tabSize: options.tabSize, insertSpaces: options.insertSpaces };
  const document = TextDocument.create('file:///check.xosc', 'xosc', 1, text);
  const formatted = formatXml(text, options, range);
  const { edits, refusal } = formattingEdits(document, editor, options.maxLineWidth, range);
  assert.equal(refusal, formatted.ok ? undefined : formatted.message, name);
  if (!formatted.ok) return 0;
  assert.equal(applyTextEditsAsSpecified(text, edits), formatted.text, `${name}: the editor's text is not the formatter's`);
  // Each change cut alone: what the editor gets as separate edits, or splits the one edit into past the limit.
  const separate = formatted.edits.flatMap((edit) => editorEdits(text, { edits: [edit], text: '' }));
  // What the extension hands VS Code (client/src/formatEdits.ts): the separate edits, however the server sent them.
  const split = splitFormatReply(document, edits, (start, end, newText) => ({ range: { start, end }, newText })) ?? [];
  assert.equal(applyTextEditsAsSpecified(text, split), formatted.text, `${name}: the split edits do not read as the formatter's text`);
  assert.deepEqual(
    split.map((edit) => ({ start: document.offsetAt(edit.range.start), end: document.offsetAt(edit.range.end), newText: edit.newText })),
    separate,
    `${name}: the client's edits differ from the separate edits`,
  );
  if (separate.length <= SEPARATE_EDITS_UP_TO) assert.equal(edits.length, separate.length, name);
  else assert.equal(edits.length, 1, `${name}: ${separate.length} changes`);
  if (!range) {
    const again = formattingEdits(TextDocument.create('file:///again.xosc', 'xosc', 1, formatted.text), editor, options.maxLineWidth);
    assert.deepEqual(again.edits, [], `${name}: an already formatted file got edits`);
  }
  return edits.length;
}

describe('Format Document and Format Selection: the edits an editor applies', () => {
  const two: FormatOptions = { tabSize: 2, insertSpaces: true, maxLineWidth: 120 };

  it('cuts each edit to what changes: an indentation is an insertion at the line start, keeping the line end', () => {
    const text = '<A>\n<B/>\n  <C/>\n</A>\n';
    const { edits } = formattingEdits(TextDocument.create('file:///a.xosc', 'xosc', 1, text), { tabSize: 2, insertSpaces: true }, 120);
    assert.deepEqual(edits, [{ range: { start: { line: 1, character: 0 }, end: { line: 1, character: 0 } }, newText: '  ' }]);
    // A CRLF stays whole: no edit starts or ends between its CR and LF.
    const crlf = '<A>\r\n<B>\r\n\r\n\r\n<C/></B></A>';
    const reply = formattingEdits(TextDocument.create('file:///b.xosc', 'xosc', 1, crlf), { tabSize: 2, insertSpaces: true }, 120).edits;
    const formatted = formatXml(crlf, two);
    assert.ok(formatted.ok && formatted.text.includes('\r\n    <C/>\r\n'));
    // The applier refuses a position inside a line end.
    assert.equal(applyTextEditsAsSpecified(crlf, reply), formatted.text);
    assert.ok(
      reply.every((edit) => !edit.newText.startsWith('\n')),
      JSON.stringify(reply),
    );
  });

  it(`sends one edit past ${SEPARATE_EDITS_UP_TO} changes, which splits back into the separate edits`, () => {
    const text = messy(400);
    const formatted = formatXml(text, two);
    assert.ok(formatted.ok && formatted.edits.length > SEPARATE_EDITS_UP_TO);
    for (const [ending, convert] of lineEnds) assert.equal(checkReply(`messy ${ending}`, convert(text), two), 1, ending);
    // Just under the limit, each change is its own edit.
    const small = messy(100);
    const count = checkReply('messy, small', small, two);
    assert.ok(count > 100 && count <= SEPARATE_EDITS_UP_TO, `${count} edits`);
    // Format Selection of many lines: one edit too, inside the selection.
    const lines = text.split('\n');
    const start = lines.slice(0, 100).join('\n').length + 1;
    const end = lines.slice(0, 2500).join('\n').length;
    assert.equal(checkReply('messy, lines 101 to 2500', text, two, { start, end }), 1);
  });

  it('splits a change of white space only, and refuses any other change', () => {
    assert.deepEqual(whitespaceEdits('<A>\n<B/>\n</A>', '<A>\n  <B/>\n</A>'), [{ start: 4, end: 4, newText: '  ' }]);
    assert.deepEqual(whitespaceEdits('<A x = "1"/>', '<A x="1"/>'), [
      { start: 4, end: 5, newText: '' },
      { start: 6, end: 7, newText: '' },
    ]);
    assert.deepEqual(whitespaceEdits('<A/>', '<A/>'), []);
    // A reply the client does not split: several edits, or one that changes more than white space.
    const document = TextDocument.create('file:///c.xosc', 'xosc', 1, '<A>\n<B/>\n</A>');
    const make = () => assert.fail('split');
    const several = [
      { range: { start: { line: 1, character: 0 }, end: { line: 1, character: 0 } }, newText: '  ' },
      { range: { start: { line: 2, character: 0 }, end: { line: 2, character: 0 } }, newText: '' },
    ];
    assert.equal(splitFormatReply(document, several, make), several);
    const other = [{ range: { start: { line: 1, character: 1 }, end: { line: 1, character: 2 } }, newText: 'C' }];
    assert.equal(splitFormatReply(document, other, make), other);
    for (const [before, after] of [
      ['<A/>', '<B/>'],
      ['<A/>', '<A/>x'],
      ['<A/>x', '<A/>'],
      ['<A/>', '<A />x'],
    ])
      assert.equal(whitespaceEdits(before, after), undefined, `${before} -> ${after}`);
  });

  it("reads as the formatter's text on the test fixtures, LF, CRLF and CR, whole and selected", () => {
    const files = xoscFiles(path.join(repoRoot, 'test', 'fixtures'));
    assert.ok(files.length >= 5, `${files.length} fixtures`);
    for (const file of files) {
      const original = fs.readFileSync(file, 'utf8');
      for (const [ending, convert] of lineEnds) {
        const text = convert(original);
        const name = `${path.relative(repoRoot, file)} ${ending}`;
        checkReply(name, text, two);
        checkReply(`${name}, tabs`, text, { tabSize: 4, insertSpaces: false, maxLineWidth: 40 });
        checkReply(`${name}, a third`, text, two, { start: Math.floor(text.length / 3), end: Math.floor((2 * text.length) / 3) });
      }
    }
  });

  describe('on every corpus file', function () {
    const corpus = path.join(sharedDir, 'corpus');
    before(function () {
      if (!fs.existsSync(corpus)) {
        console.log(`    (skipped: ${corpus} is absent)`);
        this.skip();
      }
    });

    it("reads as the formatter's text, whole and selected, and a formatted file gets no edits", () => {
      const files = xoscFiles(corpus);
      assert.ok(files.length >= 100, `expected the corpus, found ${files.length} .xosc files`);
      let edited = 0;
      for (const file of files) {
        const text = fs.readFileSync(file, 'utf8');
        const name = path.relative(corpus, file);
        edited += checkReply(name, text, { ...detectIndentation(text), maxLineWidth: 120 });
        checkReply(`${name}, tabs`, text, { tabSize: 4, insertSpaces: false, maxLineWidth: 40 });
        checkReply(`${name}, CRLF`, text.replace(/\r?\n/g, '\r\n'), two);
        checkReply(`${name}, a selection`, text, two, { start: Math.floor(text.length / 4), end: Math.floor(text.length / 2) });
      }
      assert.ok(edited > 0, 'no corpus file got an edit: the test would show nothing');
    });
  });
});
