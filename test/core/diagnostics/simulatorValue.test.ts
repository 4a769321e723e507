import * as assert from 'node:assert/strict';
import {
  comparedExactly,
  differenceMatters,
  SIMULATOR_VALUE,
  UNSEEN_DIFFERENCE,
} from '../../../server/src/core/diagnostics/simulatorValue';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed, trigger } from './semanticSupport';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../../server/src/core/flatten';
import { diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { temporaryWorkspace } from '../../support/workspace';

/** A ManeuverGroup whose one Event sets Ego's speed to `value` when `condition` (a ByValueCondition's content) holds. */
const groupStartedBy = (value: string, condition: string): string => group(speed(value)).replace('<StartTrigger/>', trigger(condition));

/**
 * Euro NCAP's pattern: a speed in km/h divided by 3.6 (esmini keeps 2.777778) times a time gives a start position, which esmini
 * computes as 100.000008 where the standard gives 100; the same rounding where it can change what runs.
 */
const ROUNDING = roadScenario({
  parameters: [
    '<ParameterDeclaration name="Speed" parameterType="double" value="${10 / 3.6}"/>',
    '<ParameterDeclaration name="StartS" parameterType="double" value="${$Speed * 36}"/>',
    '<ParameterDeclaration name="Threshold" parameterType="double" value="${$Speed * 36}"/>',
    '<ParameterDeclaration name="Third" parameterType="double" value="${1 / 3}"/>',
    '<ParameterDeclaration name="Count" parameterType="int" value="${$Third * 3}"/>',
    '<ParameterDeclaration name="Milli" parameterType="double" value="${1 / 3000}"/>',
    '<ParameterDeclaration name="Gap" parameterType="double" value="${$Milli * 1000}"/>',
  ].join('\n    '),
  groups: [
    group(speed('$StartS') + speed('$Gap')),
    groupStartedBy('${$Speed * 36}', '<SimulationTimeCondition value="${$Speed * 36}" rule="greaterThan"/>'),
    groupStartedBy('1', '<SimulationTimeCondition value="${$Speed * 72}" rule="equalTo"/>'),
    groupStartedBy('2', '<ParameterCondition parameterRef="Count" value="$Threshold" rule="greaterThan"/>'),
    // maximumExecutionCount is an unsignedInt: esmini's 0.999999 for the standard's 1 runs the group 0 times to its atoi().
    group(speed('3')).replace('maximumExecutionCount="1"', 'maximumExecutionCount="${$Third * 3}"'),
  ],
});

/** Where each simulator-value warning is: the declaration's name, or the text of its range. */
async function warnedLines(text: string): Promise<string[]> {
  const lines = text.split('\n');
  const root = temporaryWorkspace({ 'main.xosc': text });
  // With the schema, as check reads it: the schema's attribute types say which attribute reads an integer.
  const flattener = new Flattener(new ScenarioStore({ root }), 'asam', { version: 'auto' });
  const analysis = await flattener
    .analyze(diskRef(path.join(root, 'main.xosc')))
    .finally(() => fs.rmSync(root, { recursive: true, force: true }));
  const problems = analysis.problems.filter((problem) => problem.code === 'simulator-value');
  for (const problem of problems) assert.equal(problem.severity, SIMULATOR_VALUE.severity);
  return problems.map((problem) => {
    const line = lines[problem.range.start.line];
    return /<ParameterDeclaration name="(\w+)"/.exec(line)?.[1] ?? line.slice(problem.range.start.character, problem.range.end.character);
  });
}

/** Where the document checks report it otherwise: test/core/values.test.ts (esmini's readings of expressions). */
describe('diagnostics: simulator-value', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(SIMULATOR_VALUE.code, 'simulator-value');
    assert.equal(SIMULATOR_VALUE.severity, 'warning');
    assert.equal(ruleIdOf('simulator-value'), SIMULATOR_VALUE.rule.qcRule ?? 'modular2simple:simulator-value');
  });

  it("warns about esmini's six-decimal rounding only where it can change what runs (an integer, an exact comparison, a value it loses)", async () => {
    assert.deepEqual((await warnedLines(ROUNDING)).sort(), [
      // equalTo compares exactly.
      '${$Speed * 72}',
      // An integer attribute reads the rounded double whole.
      '${$Third * 3}',
      // Count is an int: the standard's 1/3*3 is 1, esmini's 0.333333*3 is 0.999999, which atoi() makes 0.
      'Count',
      // Gap: esmini's 0.000333 * 1000 is 0.333 where the standard gives 0.333333, a thousandth of it lost.
      'Gap',
      // Threshold is the value of a ParameterCondition: a stored value compared, where any difference can flip the outcome.
      'Threshold',
    ]);
  });

  it('compares exactly the values of conditions on stored values, of actions storing them, and of equalTo and notEqualTo', () => {
    assert.ok(comparedExactly('ParameterCondition', 'value', 'greaterThan'));
    assert.ok(comparedExactly('VariableSetAction', 'value', undefined));
    assert.ok(comparedExactly('SpeedCondition', 'value', 'equalTo'));
    assert.ok(comparedExactly('TimeHeadwayCondition', 'value', 'notEqualTo'));
    assert.ok(!comparedExactly('SpeedCondition', 'value', 'greaterOrEqual'));
    assert.ok(!comparedExactly('TimeHeadwayCondition', 'freespace', 'equalTo'));
    assert.ok(!comparedExactly('AbsoluteTargetSpeed', 'value', undefined));
  });

  it('takes a quantity to differ beyond a ten-thousandth of its value (absolute below 1), anything else at any difference', () => {
    assert.equal(UNSEEN_DIFFERENCE, 1e-4);
    assert.ok(!differenceMatters(100, 100.000002, false));
    assert.ok(!differenceMatters(150.527274222, 150.527439, false));
    assert.ok(differenceMatters(100, 100.02, false));
    assert.ok(differenceMatters(0.333333, 0.333, false));
    assert.ok(differenceMatters(100, 100.000002, true));
    assert.ok(differenceMatters(1, 0, false));
    assert.ok(differenceMatters(true, false, false));
    assert.ok(differenceMatters(Infinity, 1e308, false));
    assert.ok(!differenceMatters(NaN, NaN, false));
  });
});
