import * as assert from 'node:assert/strict';
import { OUT_OF_RANGE, outOfRangeWording } from '../../../server/src/core/diagnostics/outOfRange';
import { roadScenario } from '../../support/fixtures';
import { semanticProblemsOf, wordingOf } from './support';

/** A friction factor below zero, written as a parameter. */
const FRICTION = { element: 'RoadCondition', attribute: 'frictionScaleFactor', value: -0.2, written: '$Friction', range: '[0..inf[' };

describe('diagnostics: out-of-range', () => {
  it('names the attribute, the value and what it was written as, the range and its model class; a warning where esmini reads it', () => {
    assert.deepEqual(outOfRangeWording(FRICTION), {
      severity: 'error',
      code: 'out-of-range',
      message: "RoadCondition frictionScaleFactor -0.2 (from $Friction) is outside the standard's range [0..inf[",
    });
    assert.deepEqual(
      outOfRangeWording({
        element: 'Lane',
        attribute: 'x',
        value: -1,
        range: '[0..inf[',
        modelClass: 'Dist',
        reading: { by: 'esmini', text: 'uses its magnitude' },
      }),
      {
        severity: 'warning',
        code: 'out-of-range',
        message:
          "Lane x -1 is outside the standard's range [0..inf[ (class Dist of the ASAM model) (RA Consulting's checker reports it as an error); esmini uses its magnitude",
      },
    );
    assert.equal(OUT_OF_RANGE.severity, 'error');
  });

  it('is what the document checks report on a value outside its range, evaluated through a parameter', async () => {
    const environment = `<GlobalAction><EnvironmentAction><Environment name="env"><TimeOfDay animation="false" dateTime="2026-01-01T12:00:00"/><Weather><Sun azimuth="0" elevation="1" illuminance="1000"/><Fog visualRange="1000"/><Precipitation precipitationType="dry" precipitationIntensity="0"/></Weather><RoadCondition frictionScaleFactor="$Friction"/></Environment></EnvironmentAction></GlobalAction>`;
    const parameters = '<ParameterDeclaration name="Friction" parameterType="double" value="-0.2"/>';
    const problems = await semanticProblemsOf(roadScenario({ init: environment, parameters, groups: [] }));
    assert.deepEqual(problems.filter((problem) => problem.code === 'out-of-range').map(wordingOf), [outOfRangeWording(FRICTION)]);
  });
});
