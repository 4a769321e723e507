import * as assert from 'node:assert/strict';
import {
  keyForms,
  keyMatches,
  overridableAttributes,
  planOverrides,
  positionedKeyForms,
  shortestUnambiguousKey,
} from '../../server/src/core/keys';
import { findGroup, parseScenario } from '../../server/src/core/model';
import { scenario, simpleGroup } from '../support/fixtures';

const model = parseScenario(
  scenario(simpleGroup('G', '              <Position><WorldPosition parameterAttributes="y" x="0" y="9"/></Position>\n')),
);
const group = findGroup(model, 'G')!;
const targets = overridableAttributes(model, group);

function parameters(...entries: [string, string][]) {
  const text = scenario(
    `        <ManeuverGroup name="Outer"><ScenarioReference scenarioFileName="x.xosc"><ManeuverGroupReference maneuverGroupName="G">${entries
      .map(([key, value]) => `<ParameterReference key="${key}" value="${value}"/>`)
      .join('')}</ManeuverGroupReference></ScenarioReference></ManeuverGroup>\n`,
  );
  return parseScenario(text).references[0].groupReferences[0].parameters;
}

describe('core: override keys (SPEC 5)', () => {
  it('lists every attribute named in parameterAttributes, with its path and default', () => {
    const listed = targets.map((t) => `${t.path.join('.')}.${t.attributeName}=${t.defaultValue}`);
    assert.ok(listed.includes('ManeuverGroup.Maneuver.Event.Action.SpeedActionTarget.AbsoluteTargetSpeed.value=10'));
    assert.ok(listed.includes('ManeuverGroup.Maneuver.Event.Action.Position.WorldPosition.y=2'));
    assert.ok(listed.includes('ManeuverGroup.Maneuver.Event.Condition.delay=0'));
  });

  it('matches a key on a suffix of the element path', () => {
    const x = targets.find((t) => t.attributeName === 'x')!;
    assert.ok(keyMatches('x', x));
    assert.ok(keyMatches('WorldPosition.x', x));
    assert.ok(keyMatches('Position.WorldPosition.x', x));
    assert.ok(!keyMatches('Route.WorldPosition.x', x));
    assert.ok(!keyMatches('Position.x', x), 'middle names must be the nearest ancestors');
  });

  it('does not take a key that merely ends like an attribute (relay vs y)', () => {
    const y = targets.filter((t) => t.attributeName === 'y');
    assert.ok(y.every((target) => !keyMatches('relay', target)));
    const plan = planOverrides(targets, parameters(['relay', '5']));
    assert.equal(plan.unknown.length, 1);
  });

  it('applies the most specific key, whatever the order', () => {
    for (const order of [0, 1]) {
      const entries: [string, string][] = [
        ['y', 'bare'],
        ['Action.Position.WorldPosition.y', 'specific'],
      ];
      if (order) entries.reverse();
      const plan = planOverrides(targets, parameters(...entries));
      const firstY = targets.find((t) => t.attributeName === 'y' && t.path.includes('Action'))!;
      assert.equal(plan.applied.get(firstY)?.value, 'specific');
      const secondY = targets.find((t) => t.attributeName === 'y' && !t.path.includes('Action'))!;
      assert.equal(plan.applied.get(secondY)?.value, 'bare');
    }
  });

  it('suggests the closest valid key for an unknown one', () => {
    const plan = planOverrides(targets, parameters(['AbsoluteTargetSped.value', '1']));
    assert.equal(plan.unknown[0].suggestion, 'AbsoluteTargetSpeed.value');
  });

  it('reports a key that reaches an attribute without default', () => {
    const noDefault = parseScenario(
      scenario(
        `        <ManeuverGroup name="G"><Actors><EntityRef entityRef="car"/></Actors><Speed parameterAttributes="value,limit" value="1"/></ManeuverGroup>\n`,
      ),
    );
    const listed = overridableAttributes(noDefault, noDefault.groups[0]);
    const plan = planOverrides(listed, parameters(['limit', '3']));
    assert.equal(plan.withoutDefault.length, 1);
    assert.equal(plan.withoutDefault[0].target.attributeName, 'limit');
  });

  it('offers the shortest unambiguous key form first', () => {
    const value = targets.find((t) => t.attributeName === 'value')!;
    assert.equal(shortestUnambiguousKey(value, targets), 'value');
    const y = targets.find((t) => t.attributeName === 'y')!;
    assert.equal(shortestUnambiguousKey(y, targets), 'Action.Position.WorldPosition.y');
    assert.equal(keyForms(value)[0], 'value');
  });
  it("tells two attributes of one path apart by position: Event[2] (the project's addition to SPEC 5)", () => {
    // Two Events of one Maneuver: every plain key of the second speed also reaches the first.
    const twice = parseScenario(
      scenario(
        simpleGroup('T').replace(
          /( *<Event name="Go"[\s\S]*?<\/Event>\n)/,
          (event: string) => event + event.replace('name="Go" priority', 'name="Again" priority').replace('value="10"', 'value="20"'),
        ),
      ),
    );
    const all = overridableAttributes(twice, findGroup(twice, 'T')!);
    const speeds = all.filter((t) => t.element.name === 'AbsoluteTargetSpeed');
    assert.equal(speeds.length, 2);
    const [first, second] = speeds;
    assert.ok(
      keyForms(second).every((form) => keyMatches(form, first)),
      'no plain key tells them apart',
    );
    assert.equal(shortestUnambiguousKey(second, all), 'Event[2].Action.SpeedActionTarget.AbsoluteTargetSpeed.value');
    assert.ok(keyMatches('Event[1].Action.SpeedActionTarget.AbsoluteTargetSpeed.value', first));
    assert.ok(!keyMatches('Event[1].Action.SpeedActionTarget.AbsoluteTargetSpeed.value', second));
    assert.ok(!keyMatches('Event[3].Action.SpeedActionTarget.AbsoluteTargetSpeed.value', second));
    assert.ok(!keyMatches('Event[x].Action.SpeedActionTarget.AbsoluteTargetSpeed.value', second), 'a malformed position matches nothing');
    assert.ok(positionedKeyForms(second).includes('Event[2].Action.SpeedActionTarget.AbsoluteTargetSpeed.value'));
    // The positioned key is more specific than the plain one of the same length, whatever the order.
    for (const order of [0, 1]) {
      const entries: [string, string][] = [
        ['Event.Action.SpeedActionTarget.AbsoluteTargetSpeed.value', 'both'],
        ['Event[2].Action.SpeedActionTarget.AbsoluteTargetSpeed.value', 'second'],
      ];
      if (order) entries.reverse();
      const plan = planOverrides(all, parameters(...entries));
      assert.equal(plan.applied.get(first)?.value, 'both');
      assert.equal(plan.applied.get(second)?.value, 'second');
      assert.deepEqual(plan.unknown, []);
    }
  });

  it('gives two positions where one does not tell apart, before giving every position', () => {
    // Two Events of one Maneuver, each with two Conditions: the condition's delay needs its Event and its Condition.
    const condition = /( *<Condition parameterAttributes="delay"[\s\S]*?<\/Condition>\n)/;
    const oneEvent = simpleGroup('T').replace(
      condition,
      (written: string) =>
        `<StartTrigger><ConditionGroup>\n${written}${written.replace('name="Start"', 'name="Also"')}</ConditionGroup></StartTrigger>\n`,
    );
    const twice = parseScenario(
      scenario(
        oneEvent.replace(
          /( *<Event name="Go"[\s\S]*?<\/Event>\n)/,
          (event: string) => event + event.replace('name="Go" priority', 'name="Again" priority'),
        ),
      ),
    );
    const all = overridableAttributes(twice, findGroup(twice, 'T')!);
    const delays = all.filter((t) => t.attributeName === 'delay');
    assert.equal(delays.length, 4);
    assert.deepEqual(
      delays.map((delay) => shortestUnambiguousKey(delay, all)),
      [1, 2].flatMap((event) => [1, 2].map((condition) => `Event[${event}].StartTrigger.ConditionGroup.Condition[${condition}].delay`)),
    );
    delays.forEach((delay, index) =>
      assert.deepEqual(
        delays.filter((other) => keyMatches(shortestUnambiguousKey(delay, all), other)),
        [delays[index]],
      ),
    );
  });
});
