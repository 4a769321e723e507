import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as ts from 'typescript';
import { diagnosticOf, DIAGNOSTICS, SKIPPED_BY_FORCE } from '../../../server/src/core/diagnostics';
import { EXPRESSION_CODES } from '../../../server/src/core/diagnostics/expressionWords';
import { PROBLEM_FIXES } from '../../../server/src/features/fixes';
import { PROBLEM_CODE_LIST } from '../../../server/src/core/problems';
import { RULES } from '../../../server/src/core/rules';
import { repoRoot } from '../../support/paths';

const MODULES = path.join(repoRoot, 'server/src/core/diagnostics');

/** The string literals an expression may be: `'a'`, or either side of `x ? 'a' : 'b'`. */
function literalsOf(expression: ts.Expression): string[] {
  if (ts.isStringLiteralLike(expression)) return [expression.text];
  if (ts.isParenthesizedExpression(expression)) return literalsOf(expression.expression);
  if (ts.isConditionalExpression(expression)) return [...literalsOf(expression.whenTrue), ...literalsOf(expression.whenFalse)];
  return [];
}

/** The kinds of an expression's facts (`kind: 'syntax'`), each a code's (EXPRESSION_CODES). */
const EXPRESSION_KINDS: ReadonlySet<string> = new Set(Object.keys(EXPRESSION_CODES));

/**
 * The places of a source outside core/diagnostics/ that word a problem themselves: an object with a problem
 * code (or an expression fact's kind) written as a literal and a message that is not the call of a function
 * imported from a diagnostic's module, or an object that spreads a module's wording (`...xWording()`) and then
 * gives its own message.
 */
function ownWordings(file: string, text: string, codes: ReadonlySet<string>): string[] {
  const source = ts.createSourceFile(file, text, ts.ScriptTarget.Latest, true);
  const fromModules = new Set<string>();
  for (const statement of source.statements) {
    if (!ts.isImportDeclaration(statement) || !ts.isStringLiteral(statement.moduleSpecifier)) continue;
    if (!/(^|\/)diagnostics(\/|$)/.test(statement.moduleSpecifier.text)) continue;
    const bindings = statement.importClause?.namedBindings;
    if (bindings && ts.isNamedImports(bindings)) for (const element of bindings.elements) fromModules.add(element.name.text);
  }
  const isModuleCall = (expression: ts.Expression) =>
    ts.isCallExpression(expression) && ts.isIdentifier(expression.expression) && fromModules.has(expression.expression.text);
  const found: string[] = [];
  const visit = (node: ts.Node): void => {
    if (ts.isObjectLiteralExpression(node)) {
      const named = (name: string) =>
        node.properties.find(
          (property): property is ts.PropertyAssignment | ts.ShorthandPropertyAssignment =>
            (ts.isPropertyAssignment(property) || ts.isShorthandPropertyAssignment(property)) &&
            ts.isIdentifier(property.name) &&
            property.name.text === name,
        );
      const message = named('message');
      const code = named('code');
      const kind = named('kind');
      const worded = message && !(ts.isPropertyAssignment(message) && isModuleCall(message.initializer));
      const literalCodes = [
        ...(code && ts.isPropertyAssignment(code) ? literalsOf(code.initializer).filter((name) => codes.has(name)) : []),
        ...(kind && ts.isPropertyAssignment(kind) ? literalsOf(kind.initializer).filter((name) => EXPRESSION_KINDS.has(name)) : []),
      ];
      const spreadsWording = node.properties.some((property) => ts.isSpreadAssignment(property) && isModuleCall(property.expression));
      const line = source.getLineAndCharacterOfPosition(node.getStart(source)).line + 1;
      if (worded && literalCodes.length > 0) found.push(`${file}:${line}: ${literalCodes.join(', ')} worded here`);
      else if (message && spreadsWording) found.push(`${file}:${line}: a module's wording with a message of its own`);
    }
    ts.forEachChild(node, visit);
  };
  visit(source);
  return found;
}
/** The files of the folder that are no diagnostic's module. */
const SHARED = ['definition.ts', 'expressionFacts.ts', 'expressionWords.ts', 'index.ts', 'qcRules.ts', 'schemaFindings.ts'];

/** The expression's parser and evaluators, and the values they read: they report facts, which the codes' modules word. */
const EXPRESSION_PRODUCERS = ['evaluator.ts', 'expressionEvaluation.ts', 'expressionParser.ts', 'esminiValues.ts', 'values.ts'].map(
  (file) => `server/src/core/semantics/${file}`,
);

/** Every property or member named `message` a source declares or writes (`{ message: ... }`, `message: string`). */
function messageSites(file: string, text: string): string[] {
  const source = ts.createSourceFile(file, text, ts.ScriptTarget.Latest, true);
  const found: string[] = [];
  const visit = (node: ts.Node): void => {
    if (
      (ts.isPropertyAssignment(node) ||
        ts.isShorthandPropertyAssignment(node) ||
        ts.isPropertySignature(node) ||
        ts.isPropertyDeclaration(node)) &&
      ts.isIdentifier(node.name) &&
      node.name.text === 'message'
    )
      found.push(`${file}:${source.getLineAndCharacterOfPosition(node.getStart(source)).line + 1}: a message worded here`);
    ts.forEachChild(node, visit);
  };
  visit(source);
  return found;
}

/** `unknown-key` -> `unknownKey`: the name of a code's module. */
function moduleName(code: string): string {
  return code.replace(/-(\w)/g, (_, letter: string) => letter.toUpperCase());
}

describe('diagnostics: one module per diagnostic, registered in one list', () => {
  it('lists each code once, and only codes of problems.ts', () => {
    const codes = DIAGNOSTICS.map((definition) => definition.code);
    assert.deepEqual([...new Set(codes)], codes, 'a code listed twice');
    for (const code of codes) assert.ok((PROBLEM_CODE_LIST as readonly string[]).includes(code), `${code} is no problem code`);
  });

  it('has one module file per listed code, named after it, and no module left out of the list', () => {
    const files = fs
      .readdirSync(MODULES)
      .filter((name) => name.endsWith('.ts') && !SHARED.includes(name))
      .sort();
    assert.deepEqual(files, DIAGNOSTICS.map((definition) => `${moduleName(definition.code)}.ts`).sort());
    for (const definition of DIAGNOSTICS) {
      const text = fs.readFileSync(path.join(MODULES, `${moduleName(definition.code)}.ts`), 'utf8');
      assert.equal(text.match(/defineDiagnostic\(/g)?.length, 1, `${definition.code}: one definition in its module`);
      assert.ok(text.includes(`code: '${definition.code}'`), `${definition.code}: defined in its own module`);
    }
  });

  it('lists every problem code: a code that problems.ts names, and a producer can report, has its module', () => {
    assert.deepEqual(DIAGNOSTICS.map((definition) => definition.code).sort(), [...PROBLEM_CODE_LIST].sort());
  });

  it("fixes each code in one place: its module's fixes, which the editor's one adapter makes code actions", () => {
    const fixed = PROBLEM_FIXES.flatMap((fix) => fix.codes);
    assert.deepEqual([...new Set(fixed)], fixed, 'a code fixed twice');
    const editorOnly = PROBLEM_FIXES.filter((fix) => fix.codes.some((code) => !diagnosticOf(code)?.fixes)).flatMap((fix) => fix.codes);
    assert.deepEqual(editorOnly, []);
    assert.deepEqual(
      fixed.sort(),
      DIAGNOSTICS.filter((definition) => definition.fixes)
        .map((definition) => definition.code)
        .sort(),
    );
  });

  it("names each listed code's rule from its module", () => {
    for (const definition of DIAGNOSTICS) assert.equal(RULES[definition.code], definition.rule);
  });

  it('leaves no decision to the text of a message: no source tests, searches or compares one', () => {
    // `x.message.includes(...)`, `.startsWith(`, `.match(`..., `/re/.test(x.message)`, `x.message === ...`, a printed line searched for its severity.
    const decisions = [
      /\.message\s*\.\s*(includes|startsWith|endsWith|match|matchAll|search|indexOf|lastIndexOf|split)\(/,
      /\.(test|exec)\(\s*[\w.()]*\.message\b/,
      /\.message\s*[!=]==|[!=]==\s*[\w.]*\.message\b/,
      /\.includes\(': (error|warning): '\)/,
    ];
    const found: string[] = [];
    const visit = (folder: string): void => {
      for (const entry of fs.readdirSync(path.join(repoRoot, folder), { withFileTypes: true })) {
        const relative = `${folder}/${entry.name}`;
        if (entry.isDirectory()) visit(relative);
        else if (entry.name.endsWith('.ts'))
          fs.readFileSync(path.join(repoRoot, relative), 'utf8')
            .split('\n')
            .forEach((line, index) => {
              if (decisions.some((decision) => decision.test(line))) found.push(`${relative}:${index + 1}: ${line.trim()}`);
            });
      }
    };
    ['server/src', 'client/src', 'common/src'].forEach(visit);
    assert.deepEqual(found, []);
  });

  it("leaves the wording to each code's module: no producer builds a message for a code itself", () => {
    const codes = new Set<string>(PROBLEM_CODE_LIST);
    const found: string[] = [];
    const visit = (folder: string): void => {
      for (const entry of fs.readdirSync(path.join(repoRoot, folder), { withFileTypes: true })) {
        const relative = `${folder}/${entry.name}`;
        if (entry.isDirectory()) {
          if (relative !== 'server/src/core/diagnostics') visit(relative);
        } else if (entry.name.endsWith('.ts'))
          found.push(...ownWordings(relative, fs.readFileSync(path.join(repoRoot, relative), 'utf8'), codes));
      }
    };
    ['server/src', 'client/src', 'common/src'].forEach(visit);
    assert.deepEqual(found, []);
    // What it finds: a message of its own beside a literal code, or after a module's wording; a module's message passes.
    const producer = [
      "import { noActorWording, cycleMessage } from '../diagnostics/noActor';",
      "const a = { code: 'unknown-key', message: `key ${key}` };",
      "const b = { severity: 'error', code: found ? 'no-actor' : 'cycle', message };",
      "const c = { ...noActorWording(group), message: 'other words' };",
      "const d = { code: 'cycle', message: cycleMessage(files) };",
      "const e = { code: 'simulator', message: finding.message };",
      "const f = { kind: 'division-by-zero', message: `division by zero` };",
      "const g = { kind: 'binary', message: 'an expression node is no fact' };",
    ].join('\n');
    assert.deepEqual(ownWordings('x.ts', producer, codes), [
      'x.ts:2: unknown-key worded here',
      'x.ts:3: no-actor, cycle worded here',
      "x.ts:4: a module's wording with a message of its own",
      'x.ts:6: simulator worded here',
      'x.ts:7: division-by-zero worded here',
    ]);
  });

  it("leaves the wording of an expression's errors to the codes' modules: its parser and evaluators report facts", () => {
    const found = EXPRESSION_PRODUCERS.flatMap((file) => messageSites(file, fs.readFileSync(path.join(repoRoot, file), 'utf8')));
    assert.deepEqual(found, []);
    // What it finds: a message written or declared, in an object, a type or a class.
    const producer = [
      "const a = { kind: 'overflow', message: 'too big' };",
      'type B = { ok: false; message: string };',
      'const c = { message };',
      "class D { message = 'x'; }",
      'const e = { kind: "overflow", fact: "result" };',
    ].join('\n');
    assert.deepEqual(messageSites('x.ts', producer), [
      'x.ts:1: a message worded here',
      'x.ts:2: a message worded here',
      'x.ts:3: a message worded here',
      'x.ts:4: a message worded here',
    ]);
  });

  it('skips under --force what the original tool ignored silently: the key and listing problems', () => {
    assert.deepEqual([...SKIPPED_BY_FORCE].sort(), ['no-default', 'unknown-key', 'unknown-parameter-attribute']);
  });
});
