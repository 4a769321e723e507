import * as assert from 'node:assert/strict';
import { expressionMessage } from '../../server/src/core/diagnostics/expressionWords';
import { esminiStopWords } from '../../server/src/core/diagnostics/simulatorValue';
import { spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Problem } from '../../server/src/core/problems';
import { ESMINI_PROFILE } from '../../server/src/core/profiles/esmini';
import { analyzeDocument, CatalogLoader, DocumentSemantics, semanticProblems, ValueResult } from '../../server/src/core/semantics';
import { atof, atoi, esminiExpression, EsminiText, glueText, sixDecimals } from '../../server/src/core/semantics/esminiValues';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { esminiBinary, requireEsmini } from '../support/esmini';
import { sharedDir } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';
import { fileHeader, openScenarioFile } from '../support/fixtures';

/**
 * Values by the standard's rules and by esmini's (SPEC 12, issue 17). The esmini texts below are
 * what esmini 3.6.0 (the build from ../shared/esmini) logs as "Expr ${...} = ... = value" for each
 * body; the last test runs esmini on the same bodies when it is built and compares line by line.
 */
const ESMINI_PARAMETERS: Record<string, string> = { h: '0.7', s: '50', D: '3', r16: '0.333333' };

const ESMINI_LOGGED: [body: string, logged: string][] = [
  ['7 % 4', '-1.0000000000'],
  ['round(2.5)', '2.0000000000'],
  ['sign(0)', '1.0000000000'],
  ['1/0', 'inf'],
  ['BrakeCondition_HWT + _ + $h', 'BrakeCondition_HWT_0.7'],
  ['$s - 6', '44.0000000000'],
  ['7 / 2', '3.5000000000'],
  ['true and true', '1 && true'],
  ['1.80E308', '1.80E308'],
  ['2 < 3', '1.0000000000'],
  ['not false', '!false'],
  ['$D + 1', '4.0000000000'],
  ['-7 % 4', '1.0000000000'],
  ['round(-3.5)', '-4.0000000000'],
  ['1/3', '0.3333333333'],
  ['$r16 * 3', '0.9999990000'],
  ['1.7976931348623157E308 + 1E308', '1.7976931348623157E3081E308'],
  ['pow(10, 308) * 10', 'inf'],
];

const lookup = (name: string): EsminiText | undefined =>
  ESMINI_PARAMETERS[name] === undefined ? undefined : { ok: true, text: ESMINI_PARAMETERS[name], rules: [] };

/** The logged value (ten decimals) and our text (six, as esmini keeps it) name the same value. */
function sameAsLogged(ours: string, logged: string): boolean {
  if (/^-?[0-9]+\.[0-9]{10}$/.test(logged)) return /^-?[0-9]+\.[0-9]{6}$/.test(ours) && Math.abs(Number(ours) - Number(logged)) <= 5e-7;
  return ours === logged;
}

const SCENARIO = openScenarioFile(
  `  <ParameterDeclarations>
    <ParameterDeclaration name="Mod" parameterType="double" value="\${7 % 4}"/>
    <ParameterDeclaration name="Half" parameterType="double" value="\${round(2.5)}"/>
    <ParameterDeclaration name="Sign" parameterType="double" value="\${sign(0)}"/>
    <ParameterDeclaration name="Same" parameterType="double" value="\${2 * 3 + 1}"/>
    <ParameterDeclaration name="Flag" parameterType="boolean" value="\${true and true}"/>
    <ParameterDeclaration name="One" parameterType="boolean" value="1"/>
    <ParameterDeclaration name="Third" parameterType="double" value="\${1 / 3}"/>
    <ParameterDeclaration name="Big" parameterType="int" value="\${2000000000 + 2000000000}"/>
    <ParameterDeclaration name="HeadwayTime_Brake" parameterType="double" value="0.7"/>
    <ParameterDeclaration name="RedLightDistance" parameterType="string" value="50"/>
    <ParameterDeclaration name="$TargetBrakeDistance" parameterType="double" value="30"/>
    <ParameterDeclaration name="Minus" parameterType="int" value="-5.0"/>
    <ParameterDeclaration name="Glued" parameterType="string" value="\${BrakeCondition_HWT + _ + $HeadwayTime_Brake}"/>
    <ParameterDeclaration name="Stop" parameterType="double" value="\${$RedLightDistance - 6}"/>
    <ParameterDeclaration name="Bare" parameterType="double" value="\${HeadwayTime_Brake * 2}"/>
    <ParameterDeclaration name="Brake" parameterType="double" value="\${$TargetBrakeDistance + 1}"/>
    <ParameterDeclaration name="Overflow" parameterType="double" value="\${1.80E308}"/>
    <ParameterDeclaration name="Sum" parameterType="double" value="\${1.7976931348623157E308 + 1E308}"/>
    <ParameterDeclaration name="Fraction" parameterType="int" value="\${7 / 2}"/>
    <ParameterDeclaration name="Short" parameterType="unsignedShort" value="\${60000 + 6000}"/>
    <ParameterDeclaration name="Zero" parameterType="double" value="\${1 / 0}"/>
    <ParameterDeclaration name="speed" parameterType="string" value="4.333"/>
    <ParameterDeclaration name="Speed" parameterType="double" value="\${$speed}"/>
    <ParameterDeclaration name="HostVehicle" parameterType="string" value="car_white"/>
    <ParameterDeclaration name="Host" parameterType="string" value="\${$HostVehicle}"/>
  </ParameterDeclarations>
  <Storyboard>
    <Init><Actions/></Init>
    <StopTrigger/>
  </Storyboard>
`,
  fileHeader({ description: 'values' }),
);

async function analyze(simulator?: 'esmini'): Promise<DocumentSemantics> {
  const root = temporaryFolder('m2s-values-');
  return analyzeDocument(
    diskRef(path.join(root, 'values.xosc')),
    parseXml(SCENARIO),
    new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })),
    false,
    simulator,
  );
}

function valueOf(semantics: DocumentSemantics, name: string): ValueResult {
  const declaration = semantics.model.root?.byName.get(name);
  assert.ok(declaration, name);
  return semantics.evaluator.declarationValue(declaration);
}

const okValue = (result: ValueResult) => (result.ok ? result.value : `error: ${result.errors[0] && expressionMessage(result.errors[0])}`);

/** The problem whose range starts on the line declaring `name`. */
function problemAt(problems: Problem[], name: string, code: string): Problem {
  const line = SCENARIO.split('\n').findIndex((text) => text.includes(`name="${name}"`));
  const found = problems.find((problem) => problem.range.start.line === line && problem.code === code);
  assert.ok(found, `${code} at ${name}: ${problems.map((problem) => `${problem.range.start.line}:${problem.code}`).join(', ')}`);
  return found;
}

/** The text of a problem's range in the scenario. */
function textOf(problem: Problem): string {
  const line = SCENARIO.split('\n')[problem.range.start.line];
  return line.slice(problem.range.start.character, problem.range.end.character);
}

describe('values by the standard and by esmini (SPEC 12)', () => {
  let standard: DocumentSemantics;
  let esmini: DocumentSemantics;
  let problems: Problem[];
  before(async () => {
    standard = await analyze();
    esmini = await analyze('esmini');
    problems = semanticProblems(standard);
  });

  it("computes esmini's text of each body as esmini 3.6.0 logs it", () => {
    for (const [body, logged] of ESMINI_LOGGED) {
      const result = esminiExpression(body, lookup);
      assert.ok(result.ok, `${body}: ${!result.ok && esminiStopWords(result.stop)}`);
      assert.ok(sameAsLogged(result.text, logged), `${body}: ours ${result.text}, esmini ${logged}`);
    }
  });

  it("follows esmini's C conversions: six decimals, atof, atoi (wrapping), text gluing", () => {
    assert.equal(sixDecimals(1 / 3), '0.333333');
    assert.equal(sixDecimals(-0), '-0.000000');
    assert.equal(sixDecimals(Infinity), 'inf');
    assert.equal(sixDecimals(1e22), '10000000000000000000000.000000');
    assert.equal(atof('44.000000'), 44);
    assert.equal(atof('1.80E308'), 1.8e308);
    assert.equal(atof('BrakeCondition'), 0);
    assert.equal(atof('inf'), Infinity);
    assert.equal(atoi('3.500000'), 3);
    assert.equal(atoi('4000000000.000000'), -294967296);
    assert.equal(glueText('a + _ + 0.7'), 'a_0.7');
    assert.equal(glueText('a+b'), 'a+b');
    assert.equal(glueText('a +b'), 'ab');
    // A number that starts with its dot is no number to esmini's tokenizer: it stops.
    const dot = esminiExpression('.5 + 1', lookup);
    assert.ok(!dot.ok && /Failed to evaluate/.test(esminiStopWords(dot.stop)));
  });

  it('gives the standard value and, where esmini computes another, both with the rule and its source', () => {
    const cases: [name: string, standardValue: unknown, esminiValue: unknown, rule: string][] = [
      ['Mod', 3, -1, 'remainder'],
      ['Half', 3, 2, 'round'],
      ['Sign', 0, 1, 'sign'],
      ['Flag', true, false, 'textGluing'],
      ['One', true, false, 'booleanConversion'],
      ['Big', 'error', -294967296, ''],
    ];
    for (const [name, standardValue, esminiValue, rule] of cases) {
      const byStandard = valueOf(standard, name);
      const byEsmini = valueOf(esmini, name);
      if (standardValue === 'error') {
        assert.ok(!byStandard.ok, `${name} is an error by the standard`);
        continue;
      }
      assert.equal(okValue(byStandard), standardValue, `${name} by the standard`);
      assert.equal(okValue(byEsmini), esminiValue, `${name} by esmini`);
      assert.ok(byStandard.ok && byStandard.differs, `${name} differs`);
      const fact = ESMINI_PROFILE.valueRules?.[rule as keyof NonNullable<typeof ESMINI_PROFILE.valueRules>];
      assert.ok(fact, rule);
      assert.ok(
        byStandard.differs.reasons.some((reason) => reason.includes(fact.source)),
        `${name}: ${byStandard.differs.reasons.join(' | ')}`,
      );
      const warning = problemAt(problems, name, 'simulator-value');
      assert.equal(warning.severity, 'warning');
      assert.match(warning.message, new RegExp(`esmini computes ${String(esminiValue)} where the standard gives ${String(standardValue)}`));
    }
    // Where both agree there is no warning, and esmini's six decimals are no difference.
    assert.equal(okValue(valueOf(esmini, 'Same')), 7);
    assert.ok(
      !problems.some((problem) => problem.code === 'simulator-value' && /Same|Third/.test(SCENARIO.split('\n')[problem.range.start.line])),
    );
    assert.equal(okValue(valueOf(esmini, 'Third')), 0.333333);
  });

  it('reads the forms esmini accepts with one clear meaning, each a warning with the standard form as its fix', () => {
    assert.equal(okValue(valueOf(standard, 'Glued')), 'BrakeCondition_HWT_0.7');
    assert.equal(okValue(valueOf(standard, 'Stop')), 44);
    assert.equal(okValue(valueOf(standard, 'Bare')), 1.4);
    assert.equal(okValue(valueOf(standard, 'Brake')), 31, '$TargetBrakeDistance resolves to the declaration name="$TargetBrakeDistance"');
    assert.equal(okValue(valueOf(standard, 'Minus')), -5);
    // A string parameter whose text is a number, alone in an expression: read as that number (esmini and the ASAM API do).
    assert.equal(okValue(valueOf(standard, 'Speed')), 4.333);
    assert.equal(okValue(valueOf(esmini, 'Speed')), 4.333);
    assert.deepEqual(problemAt(problems, 'Speed', 'lenient-value').data, { relatedReplacement: 'double' });
    // A text string parameter alone in an expression: esmini keeps the text, the standard has none.
    assert.equal(okValue(valueOf(standard, 'Host')), 'car_white');
    assert.deepEqual(problemAt(problems, 'Host', 'lenient-value').data, { suggestion: '$HostVehicle' });
    const lenient = problems.filter((problem) => problem.code === 'lenient-value');
    assert.ok(lenient.every((problem) => problem.severity === 'warning'));
    const glued = problemAt(problems, 'Glued', 'lenient-value');
    assert.equal(textOf(glued), '${BrakeCondition_HWT + _ + $HeadwayTime_Brake}');
    assert.deepEqual(glued.data, { suggestion: 'BrakeCondition_HWT_0.7' });
    const stop = problemAt(problems, 'Stop', 'lenient-value');
    assert.equal(textOf(stop), '$RedLightDistance');
    assert.deepEqual(stop.data, { relatedReplacement: 'double' });
    assert.equal(
      stop.related?.[0].range.start.line,
      SCENARIO.split('\n').findIndex((text) => text.includes('name="RedLightDistance"')),
    );
    const bare = problemAt(problems, 'Bare', 'lenient-value');
    assert.equal(textOf(bare), 'HeadwayTime_Brake');
    assert.deepEqual(bare.data, { suggestion: '$HeadwayTime_Brake' });
    const dollar = problemAt(problems, '$TargetBrakeDistance', 'lenient-value');
    assert.equal(textOf(dollar), '$TargetBrakeDistance');
    assert.deepEqual(dollar.data, { suggestion: 'TargetBrakeDistance' });
    const minus = problemAt(problems, 'Minus', 'lenient-value');
    assert.equal(textOf(minus), '-5.0');
    assert.deepEqual(minus.data, { suggestion: '-5' });
    // Nothing of these is an undeclared parameter or an error.
    assert.ok(!problems.some((problem) => problem.code === 'undeclared-parameter'));
    for (const name of ['Glued', 'Stop', 'Bare', 'Brake', 'Minus', '$TargetBrakeDistance', 'Speed', 'Host']) {
      const line = SCENARIO.split('\n').findIndex((text) => text.includes(`name="${name}"`));
      assert.ok(!problems.some((problem) => problem.range.start.line === line && problem.severity === 'error'), name);
    }
  });

  it("keeps the standard's errors, with their column: double overflow, a non-integral int, an unsignedShort out of range, division by zero", () => {
    const overflow = problemAt(problems, 'Overflow', 'overflow');
    assert.equal([overflow.severity, textOf(overflow)].join(' '), 'error 1.80E308');
    const sum = problemAt(problems, 'Sum', 'overflow');
    assert.equal([sum.severity, textOf(sum)].join(' '), 'error 1.7976931348623157E308 + 1E308');
    const fraction = problemAt(problems, 'Fraction', 'type-mismatch');
    assert.match(fraction.message, /3\.5 is not integral/);
    assert.equal(fraction.severity, 'error');
    const short = problemAt(problems, 'Short', 'type-mismatch');
    assert.match(short.message, /66000 is outside the range of an unsignedShort/);
    const zero = problemAt(problems, 'Zero', 'division-by-zero');
    assert.equal(zero.severity, 'error');
    assert.match(zero.message, /esmini computes inf/);
  });

  it('agrees with the real esmini on every body, line by line', async function () {
    requireEsmini(this);
    this.timeout(120_000);
    const directory = temporaryFolder('m2s-values-esmini-');
    const base = fs.readFileSync(path.join(sharedDir, 'corpus', 'openscenario', 'esmini', 'cut-in_simple.xosc'), 'utf8');
    const escape = (text: string) => text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/"/g, '&quot;');
    const declarations = [
      ...Object.entries(ESMINI_PARAMETERS).map(
        ([name, value]) => `<ParameterDeclaration name="${name}" parameterType="string" value="${value}"/>`,
      ),
      ...ESMINI_LOGGED.map(
        ([body], index) => `<ParameterDeclaration name="v${index}" parameterType="string" value="${escape(`\${${body}}`)}"/>`,
      ),
    ].join('\n');
    const scenario = path.join(directory, 'values.xosc');
    fs.writeFileSync(scenario, base.replace('<ParameterDeclarations>', `<ParameterDeclarations>\n${declarations}`));
    const output = await new Promise<string>((resolve, reject) => {
      const chunks: string[] = [];
      const child = spawn(esminiBinary, ['--headless', '--osc', scenario, '--fixed_timestep', '0.1', '--disable_log'], {
        cwd: directory,
        stdio: ['ignore', 'pipe', 'pipe'],
      });
      const timer = setTimeout(() => child.kill('SIGKILL'), 60_000);
      child.stdout.on('data', (chunk: Buffer) => chunks.push(chunk.toString()));
      child.stderr.on('data', (chunk: Buffer) => chunks.push(chunk.toString()));
      child.on('error', reject);
      child.on('close', () => {
        clearTimeout(timer);
        resolve(chunks.join(''));
      });
    });
    fs.rmSync(directory, { recursive: true, force: true });
    for (const [body] of ESMINI_LOGGED) {
      const line = output.split('\n').find((candidate) => candidate.includes(`Expr \${${body}} = `));
      assert.ok(line, `esmini logged no value for \${${body}}:\n${output.slice(0, 3000)}`);
      const logged = line.slice(line.lastIndexOf(' = ') + 3).trim();
      const ours = esminiExpression(body, lookup);
      assert.ok(
        ours.ok && sameAsLogged(ours.text, logged),
        `\${${body}}: ours ${ours.ok ? ours.text : esminiStopWords(ours.stop)}, esmini ${logged}`,
      );
    }
  });
});
