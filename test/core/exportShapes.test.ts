import { strict as assert } from 'node:assert';
import { sampleClothoid, sampleClothoidSpline, sampleNurbs, SAMPLE_STEP } from '../../server/src/core/export/shapes';

describe('export shapes: Clothoid, ClothoidSpline and Nurbs sampled as esmini samples them', () => {
  it('a Clothoid of constant curvature is a circle arc, a vertex every metre, the last at its end, with times along s', () => {
    const radius = 20;
    const length = Math.PI * radius; // half a circle
    const vertices = sampleClothoid({ x: 5, y: -3, hdg: 0 }, 1 / radius, 0, length, { start: 2, stop: 12 });
    assert.equal(vertices.length, Math.floor(length / SAMPLE_STEP) + 1);
    for (const vertex of vertices) assert.ok(Math.abs(Math.hypot(vertex.x - 5, vertex.y + 3 - radius) - radius) < 1e-6);
    const last = vertices[vertices.length - 1];
    assert.ok(Math.abs(last.x - 5) < 1e-6 && Math.abs(last.y - (2 * radius - 3)) < 1e-6, `${last.x}, ${last.y}`);
    assert.ok(Math.abs(Math.abs(last.h) - Math.PI) < 1e-6);
    assert.equal(vertices[0].time, 2);
    assert.ok(Math.abs((last.time ?? 0) - 12) < 1e-9);
    assert.ok(Math.abs((vertices[10].time ?? 0) - (2 + (10 / length) * 10)) < 1e-9);
    assert.equal(sampleClothoid({ x: 0, y: 0, hdg: 0 }, 0, 0, 3)[0].time, undefined, 'no times unless the shape has them');
  });

  it('a ClothoidSpline runs its segments end to end, with times per segment up to timeEnd', () => {
    const vertices = sampleClothoidSpline(
      { x: 0, y: 0, hdg: 0 },
      [
        { curvStart: 0, curvEnd: 0, length: 10, hOffset: 0, time: 0 },
        { curvStart: 0, curvEnd: 0, length: 10, hOffset: Math.PI / 2, time: 4 },
      ],
      6,
    );
    const last = vertices[vertices.length - 1];
    assert.ok(Math.abs(last.x - 10) < 1e-9 && Math.abs(last.y - 10) < 1e-9, `${last.x}, ${last.y}`);
    assert.equal(vertices.length, 21);
    assert.ok(Math.abs((vertices[5].time ?? 0) - 2) < 1e-9);
    assert.ok(Math.abs((vertices[15].time ?? 0) - 5) < 1e-9);
    assert.ok(Math.abs((last.time ?? 0) - 6) < 1e-9);
  });

  it('a Nurbs of order 2 is its control polygon; of order 3 it starts and ends at its clamped end points; times from its control points', () => {
    const line = sampleNurbs(
      2,
      [
        { x: 0, y: 0, weight: 1, time: 0 },
        { x: 10, y: 0, weight: 1, time: 5 },
      ],
      [0, 0, 1, 1],
    );
    assert.ok(Array.isArray(line));
    assert.equal(line.length, 12);
    for (const vertex of line) assert.ok(Math.abs(vertex.y) < 1e-9 && Math.abs(vertex.h) < 1e-9);
    assert.ok(Math.abs(line[line.length - 1].x - 10) < 1e-6);
    assert.ok(Math.abs((line[line.length - 1].time ?? 0) - 5) < 1e-6);
    const curve = sampleNurbs(
      3,
      [
        { x: 0, y: 0, weight: 1 },
        { x: 20, y: 0, weight: 1 },
        { x: 20, y: 20, weight: 1 },
      ],
      [0, 0, 0, 1, 1, 1],
    );
    assert.ok(Array.isArray(curve));
    assert.ok(Math.hypot(curve[0].x, curve[0].y) < 1e-9);
    const end = curve[curve.length - 1];
    assert.ok(Math.hypot(end.x - 20, end.y - 20) < 1e-3, `${end.x}, ${end.y}`);
    assert.ok(Math.abs(end.h - Math.PI / 2) < 1e-3, `${end.h}`);
    assert.equal(curve[0].time, undefined);
  });

  it('a Nurbs that cannot be evaluated says why', () => {
    const points = [
      { x: 0, y: 0, weight: 1 },
      { x: 1, y: 0, weight: 1 },
    ];
    assert.match(String(sampleNurbs(3, points, [0, 0, 1, 1])), /4 knots where 2 control points of order 3 need 5/);
    assert.match(String(sampleNurbs(0, points, [0, 1])), /order 0 is not a positive whole number/);
    assert.match(
      String(
        sampleNurbs(
          2,
          [
            { x: 1, y: 1, weight: 1 },
            { x: 1, y: 1, weight: 1 },
          ],
          [0, 0, 1, 1],
        ),
      ),
      /all lie at one place/,
    );
  });
});
