import * as assert from 'node:assert/strict';
import { evaluateGeometry, Geometry } from '../../server/src/core/opendrive/geometry';
import {
  laneBorderPoint,
  laneCenterT,
  openDriveSignals,
  parseOpenDrive,
  referencePose,
  roadPoint,
} from '../../server/src/core/opendrive/road';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiRoads } from '../support/esmini';

const close = (actual: number, expected: number, tolerance = 1e-6, what = '') =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what} ${actual} is not within ${tolerance} of ${expected}`);

function road(geometries: string, lanes = '', extra = '', length = 100): string {
  return `<?xml version="1.0"?><OpenDRIVE><header/><road id="7" length="${length}" junction="-1"><planView>${geometries}</planView>${extra}<lanes>${lanes}</lanes></road></OpenDRIVE>`;
}

describe('core: OpenDRIVE reference line', () => {
  it('line: a point along the heading', () => {
    const line: Geometry = { kind: 'line', s: 0, x: 1, y: 2, hdg: Math.PI / 2, length: 10 };
    const pose = evaluateGeometry(line, 4);
    close(pose.x, 1);
    close(pose.y, 6);
    close(pose.hdg, Math.PI / 2);
  });

  it('arc: a quarter circle of radius 10 ends at (10, 10) heading north', () => {
    const arc: Geometry = { kind: 'arc', s: 0, x: 0, y: 0, hdg: 0, length: (Math.PI / 2) * 10, curvature: 0.1 };
    const end = evaluateGeometry(arc, arc.length);
    close(end.x, 10);
    close(end.y, 10);
    close(end.hdg, Math.PI / 2);
    // Half-way: 45 degrees round the circle, x = r·sin 45°, y = r·(1 - cos 45°).
    const middle = evaluateGeometry(arc, arc.length / 2);
    close(middle.x, 10 * Math.SQRT1_2);
    close(middle.y, 10 * (1 - Math.SQRT1_2));
    // Right turn: mirrored.
    const right = evaluateGeometry({ ...arc, curvature: -0.1 }, arc.length);
    close(right.x, 10);
    close(right.y, -10);
  });

  it('spiral: matches the Fresnel integrals of a clothoid from curvature 0', () => {
    // Curvature from 0 to 1/A² · L over L; with A = 1 the point at L = sqrt(pi) is (C, S)(1)·sqrt(pi),
    // where C(1) = 0.7798934004, S(1) = 0.4382591473 (normalised Fresnel integrals, Abramowitz & Stegun table 7.7).
    const length = Math.sqrt(Math.PI);
    const spiral: Geometry = { kind: 'spiral', s: 0, x: 0, y: 0, hdg: 0, length, curvStart: 0, curvEnd: length };
    const end = evaluateGeometry(spiral, length);
    close(end.x, 0.7798934004 * Math.sqrt(Math.PI), 1e-9);
    close(end.y, 0.4382591473 * Math.sqrt(Math.PI), 1e-9);
    close(end.hdg, (length * length) / 2, 1e-12);
    // A spiral with equal start and end curvature is an arc.
    const asArc = evaluateGeometry({ kind: 'spiral', s: 0, x: 0, y: 0, hdg: 0, length: 20, curvStart: 0.05, curvEnd: 0.05 }, 20);
    const arc = evaluateGeometry({ kind: 'arc', s: 0, x: 0, y: 0, hdg: 0, length: 20, curvature: 0.05 }, 20);
    close(asArc.x, arc.x, 1e-9);
    close(asArc.y, arc.y, 1e-9);
  });

  it('poly3: s is arc length along v = u²/10, heading from the slope', () => {
    // Arc length of v = c·u² from 0 to U: (U·sqrt(1+4c²U²))/2 + asinh(2cU)/(4c).
    const c = 0.1;
    const U = 5;
    const length = (U * Math.sqrt(1 + 4 * c * c * U * U)) / 2 + Math.asinh(2 * c * U) / (4 * c);
    const poly3: Geometry = { kind: 'poly3', s: 0, x: 0, y: 0, hdg: 0, length, a: 0, b: 0, c, d: 0 };
    const end = evaluateGeometry(poly3, length);
    close(end.x, U, 1e-6);
    close(end.y, c * U * U, 1e-6);
    close(end.hdg, Math.atan(2 * c * U), 1e-6);
    // A poly3 with b = 0, c = 0, d = 0 and offset a is a line shifted sideways.
    const shifted = evaluateGeometry({ kind: 'poly3', s: 0, x: 0, y: 0, hdg: 0, length: 10, a: 2, b: 0, c: 0, d: 0 }, 3);
    close(shifted.x, 3);
    close(shifted.y, 2);
  });

  it('paramPoly3: arcLength and normalized ranges describe the same curve', () => {
    // A straight line along 45 degrees: u = p·cos45, v = p·sin45 for p in [0, 10].
    const k = Math.SQRT1_2;
    const arcLength: Geometry = {
      kind: 'paramPoly3',
      s: 0,
      x: 0,
      y: 0,
      hdg: 0,
      length: 10,
      aU: 0,
      bU: k,
      cU: 0,
      dU: 0,
      aV: 0,
      bV: k,
      cV: 0,
      dV: 0,
      pRange: 'arcLength',
    };
    const normalized: Geometry = { ...arcLength, bU: 10 * k, bV: 10 * k, pRange: 'normalized' };
    for (const geometry of [arcLength, normalized]) {
      const pose = evaluateGeometry(geometry, 4);
      close(pose.x, 4 * k);
      close(pose.y, 4 * k);
      close(pose.hdg, Math.PI / 4);
    }
    // An uneven parameter speed, u = 16·p² over p in [0, 1]: s = 1 m is still 1 m along the curve.
    const uneven: Geometry = {
      kind: 'paramPoly3',
      s: 0,
      x: 5,
      y: 0,
      hdg: 0,
      length: 16,
      aU: 0,
      bU: 0,
      cU: 16,
      dU: 0,
      aV: 0,
      bV: 0,
      cV: 0,
      dV: 0,
      pRange: 'normalized',
    };
    close(evaluateGeometry(uneven, 1).x, 6, 1e-6);
  });
});

describe('core: OpenDRIVE lanes', () => {
  const lanes = `
    <laneOffset s="0" a="0.5" b="0" c="0" d="0"/>
    <laneOffset s="50" a="0.5" b="0.01" c="0" d="0"/>
    <laneSection s="0">
      <left><lane id="2" type="sidewalk"><width sOffset="0" a="2" b="0" c="0" d="0"/></lane><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
      <center><lane id="0" type="none"/></center>
      <right><lane id="-1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/><width sOffset="20" a="3" b="0.05" c="0" d="0"/></lane></right>
    </laneSection>
    <laneSection s="60"><center><lane id="0" type="none"/></center><right><lane id="-1" type="driving"><width sOffset="0" a="4" b="0" c="0" d="0"/></lane></right></laneSection>`;

  it('parses roads, sections (with lengths) and lanes ordered left to right', () => {
    const network = parseOpenDrive(road('<geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry>', lanes));
    assert.deepEqual(network.problems, []);
    const parsed = network.byId.get('7');
    assert.ok(parsed);
    assert.deepEqual(
      parsed.laneSections.map((section) => [section.s, section.length]),
      [
        [0, 60],
        [60, 40],
      ],
    );
    assert.deepEqual(
      parsed.laneSections[0].lanes.map((lane) => lane.id),
      [2, 1, 0, -1],
    );
  });

  it('lane borders add widths outward from the lane-offset line, with several width entries and laneOffsets', () => {
    const parsed = parseOpenDrive(road('<geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry>', lanes)).byId.get('7')!;
    // At s = 10: offset 0.5; lane 1 outer border at 0.5 + 3.5, lane 2 at 0.5 + 5.5, lane -1 at 0.5 - 3.
    close(laneBorderPoint(parsed, 0, 0, 10).y, 0.5);
    close(laneBorderPoint(parsed, 0, 1, 10).y, 4);
    close(laneBorderPoint(parsed, 0, 2, 10).y, 6);
    close(laneBorderPoint(parsed, 0, -1, 10).y, -2.5);
    // At s = 30 the second width entry applies: 3 + 0.05·10.
    close(laneBorderPoint(parsed, 0, -1, 30).y, 0.5 - 3.5);
    // At s = 55 the second laneOffset applies: 0.5 + 0.01·5.
    close(laneBorderPoint(parsed, 0, 0, 55).y, 0.55);
    // Lane centers: lane -1 at s = 10 is 1.5 m right of the offset line.
    close(laneCenterT(parsed, 0, -1, 10), -1);
    close(laneCenterT(parsed, 1, -1, 70), 0.5 + 0.2 - 2);
  });

  it('geometries follow each other along s; a road point is offset to the left of the heading', () => {
    const geometries =
      '<geometry s="0" x="0" y="0" hdg="0" length="10"><line/></geometry><geometry s="10" x="10" y="0" hdg="0" length="15.707963267948966"><arc curvature="0.1"/></geometry>';
    const parsed = parseOpenDrive(road(geometries, '', '', 25.707963267948966)).byId.get('7')!;
    const end = referencePose(parsed, 25.707963267948966);
    close(end.x, 20);
    close(end.y, 10);
    const left = roadPoint(parsed, 5, 2);
    close(left.x, 5);
    close(left.y, 2);
  });

  it('superelevation projects the lateral offset onto the ground plane', () => {
    const tilted = parseOpenDrive(
      road(
        '<geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry>',
        '',
        '<lateralProfile><superelevation s="0" a="0.5" b="0" c="0" d="0"/></lateralProfile>',
      ),
    ).byId.get('7')!;
    close(roadPoint(tilted, 10, 4).y, 4 * Math.cos(0.5));
  });

  it('reports what it cannot read instead of failing', () => {
    const network = parseOpenDrive(road('<geometry s="0" x="0" y="0" hdg="0" length="10"><bogus/></geometry>'));
    assert.match(network.problems[0].message, /unsupported geometry <bogus>/);
    assert.match(parseOpenDrive('<OpenSCENARIO/>').problems[0].message, /not an OpenDRIVE file/);
    assert.ok(parseOpenDrive('<OpenDRIVE><road id="1"').problems.length > 0);
  });
});

describe('core: OpenDRIVE signals read alone', () => {
  /** What the signal rule took from parseOpenDrive before openDriveSignals: the same for every text. */
  const fromWholeParse = (text: string) => {
    const network = parseOpenDrive(text);
    const leftHandRoads = new Set(network.roads.filter((road) => road.leftHandTraffic).map((road) => road.id));
    return { hasRoads: network.roads.length > 0, signalIds: network.signalIds, leftHandRoads };
  };
  const withSignals = `<?xml version="1.0"?><OpenDRIVE><header/>
  <road id="1" length="10" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="10"><line/></geometry></planView>
    <signals><signal id="101" s="5" t="-3"/><signal id="" s="6"/><signal s="7"/></signals>
    <objects><signal id="not-a-signal"/></objects></road>
  <road id="2" length="10" junction="-1" rule="LHT"><signals><signal id="&amp;7" s="1"/></signals><signals><signal id="second-list"/></signals></road>
  <controller id="7"><control signalId="102"/><control signalId="101"/></controller>
  <junction id="9"><controller id="7"/></junction>
</OpenDRIVE>`;

  it("gives parseOpenDrive's signal ids, roads of left-hand traffic and whether it read roads, on esmini's roads and on broken or foreign texts", () => {
    const roads = fs.existsSync(esminiRoads) ? fs.readdirSync(esminiRoads).filter((name) => name.endsWith('.xodr')) : [];
    const texts = roads.map((name) => fs.readFileSync(path.join(esminiRoads, name), 'utf8'));
    texts.push(withSignals, '<OpenSCENARIO><road id="1"/></OpenSCENARIO>', '<OpenDRIVE/>', '', 'not xml', '<OpenDRIVE><road id="1"');
    // Cut anywhere, as a file being written: the tolerant parser's tree decides for both alike.
    for (let end = 0; end < withSignals.length; end += 7) texts.push(withSignals.slice(0, end));
    for (const text of texts) assert.deepEqual(openDriveSignals(text), fromWholeParse(text), text.slice(0, 200));
    // A road's first <signals> list, as parseOpenDrive reads it; ids decoded; an empty id is none.
    assert.deepEqual([...openDriveSignals(withSignals).signalIds].sort(), ['&7', '101', '102']);
    // A road's traffic rule, as parseOpenDrive reads it: right-hand unless rule="LHT".
    assert.deepEqual([...openDriveSignals(withSignals).leftHandRoads], ['2']);
    assert.ok(texts.length > 20 && roads.length > 0, "esmini's roads were read");
  });
});
