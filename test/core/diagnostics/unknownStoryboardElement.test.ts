import * as assert from 'node:assert/strict';
import { UNKNOWN_STORYBOARD_ELEMENT } from '../../../server/src/core/diagnostics/unknownStoryboardElement';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed, trigger } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: unknown-storyboard-element', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNKNOWN_STORYBOARD_ELEMENT.code, 'unknown-storyboard-element');
    assert.equal(UNKNOWN_STORYBOARD_ELEMENT.severity, 'warning');
    assert.equal(
      ruleIdOf('unknown-storyboard-element'),
      UNKNOWN_STORYBOARD_ELEMENT.rule.qcRule ?? 'modular2simple:unknown-storyboard-element',
    );
    assert.equal(UNKNOWN_STORYBOARD_ELEMENT.isData!({ suggestion: 'E' }), true);
    assert.equal(UNKNOWN_STORYBOARD_ELEMENT.isData!({ other: 'E' }), false);
  });

  it('is what the document checks report', async () => {
    const problems = (
      await semanticProblemsOf(
        roadScenario({
          groups: [
            group(speed('1')).replace(
              '<StartTrigger/>',
              trigger('<StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="Nope" state="endTransition"/>'),
            ),
          ],
        }),
      )
    ).filter((problem) => problem.code === 'unknown-storyboard-element');
    assert.deepEqual(problems.map(wordingOf), [
      { severity: 'warning', code: 'unknown-storyboard-element', message: "no Event named 'Nope'", hint: "did you mean 'E'?" },
    ]);
    assert.deepEqual(problems[0].data, { suggestion: 'E' });
  });
});
