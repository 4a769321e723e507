import { strict as assert } from 'node:assert';
import { snappedLaneAtPoint } from '../../server/src/core/opendrive/lanePosition';
import { parseOpenDrive } from '../../server/src/core/opendrive/road';
import { pointAlongRoute, routeLanes } from '../../server/src/core/opendrive/route';

/** A straight road of one right lane (-1) along x from `x`, linked as given, lane -1 linked to lane -1 at both ends. */
function road(id: string, x: number, length: number, links: string, junction = '-1'): string {
  return `
  <road id="${id}" length="${length}" junction="${junction}">
    <link>${links}</link>
    <planView><geometry s="0" x="${x}" y="0" hdg="0" length="${length}"><line/></geometry></planView>
    <lanes><laneSection s="0">
      <center><lane id="0" type="none"/></center>
      <right><lane id="-1" type="driving"><link><predecessor id="-1"/><successor id="-1"/></link><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>
  </road>`;
}

/** Road 1 (100 m) into junction 9, whose connecting roads (id, length, the road it leads to) follow it, in that order. */
function junctionNetwork(branches: [string, number, string][]): string {
  const ends = [...new Set(branches.map(([, , to]) => to))];
  return `<?xml version="1.0"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="6"><geoReference><![CDATA[+proj=tmerc +lat_0=57 +lon_0=12]]></geoReference></header>
  ${road('1', 0, 100, '<successor elementType="junction" elementId="9"/>')}
  ${branches
    .map(([id, length, to]) =>
      road(
        id,
        100,
        length,
        `<predecessor elementType="road" elementId="1" contactPoint="end"/><successor elementType="road" elementId="${to}" contactPoint="start"/>`,
        '9',
      ),
    )
    .join('')}
  ${ends.map((id) => road(id, 120, 100, '<predecessor elementType="junction" elementId="9"/>')).join('')}
  <junction id="9">
    ${branches
      .map(
        ([id], index) =>
          `<connection id="${index}" incomingRoad="1" connectingRoad="${id}" contactPoint="start"><laneLink from="-1" to="-1"/></connection>`,
      )
      .join('')}
  </junction>
</OpenDRIVE>`;
}

/** Road 1 (100 m) into junction 9, whose connecting roads 10 and 11 (both `lengths`) lead to road 2 (100 m). */
function network(lengths: [number, number]): string {
  return junctionNetwork([
    ['10', lengths[0], '2'],
    ['11', lengths[1], '2'],
  ]);
}

describe('a point along a route, as esmini plans it (core/opendrive/route)', () => {
  it('reads links, junction connections and the geoReference', () => {
    const parsed = parseOpenDrive(network([20, 25]));
    assert.deepEqual(parsed.byId.get('10')?.successor, { elementType: 'road', elementId: '2', contactPoint: 'start' });
    assert.deepEqual(parsed.byId.get('1')?.successor, { elementType: 'junction', elementId: '9', contactPoint: undefined });
    assert.equal(parsed.junctions.get('9')?.connections.length, 2);
    assert.deepEqual(parsed.junctions.get('9')?.connections[1].laneLinks, [[-1, -1]]);
    assert.equal(parsed.byId.get('2')?.laneSections[0].lanes.find((lane) => lane.id === -1)?.successor, -1);
    assert.equal(parsed.geoReference, '+proj=tmerc +lat_0=57 +lon_0=12');
  });

  it('takes the nearer connecting road, and lands on the road where the distance ends', () => {
    const roads = parseOpenDrive(network([20, 25]));
    const waypoints = [
      { roadId: '1', laneId: -1, s: 50 },
      { roadId: '2', laneId: -1, s: 30 },
    ];
    assert.deepEqual(pointAlongRoute(roads, waypoints, 10), { roadId: '1', s: 60, roads: ['1', '10', '2'] });
    assert.deepEqual(pointAlongRoute(roads, waypoints, 55), { roadId: '10', s: 5, roads: ['1', '10', '2'] });
    const onLast = pointAlongRoute(roads, waypoints, 80);
    assert.ok(typeof onLast !== 'string' && onLast.roadId === '2' && Math.abs(onLast.s - 10) < 1e-9, JSON.stringify(onLast));
    assert.match(String(pointAlongRoute(roads, waypoints, 101)), /pathS 101 lies past the route's end \(the route is 100 m long/);
  });

  it('names an ambiguous way (two connecting roads equally long) and no way (against the driving direction)', () => {
    const roads = parseOpenDrive(network([20, 20]));
    const forward = [
      { roadId: '1', laneId: -1, s: 50 },
      { roadId: '2', laneId: -1, s: 30 },
    ];
    assert.equal(
      pointAlongRoute(roads, forward, 60),
      'from waypoint 1 to waypoint 2 two ways are equally short (roads 1 > 10 > 2, and 1 > 11 > 2) and the standard names no rule to choose (esmini takes the one its file lists first): add a Waypoint on road 10 or road 11 between them to say which',
    );
    const named = forward.map((waypoint, index) => ({ ...waypoint, name: `the Waypoint at route.xosc:${40 + index}` }));
    assert.match(
      String(pointAlongRoute(roads, named, 60)),
      /^from the Waypoint at route\.xosc:40 to the Waypoint at route\.xosc:41 two ways/,
    );
    // The waypoint the message asks for settles it: the route through road 11.
    const through11 = [forward[0], { roadId: '11', laneId: -1, s: 10 }, forward[1]];
    assert.deepEqual(pointAlongRoute(roads, through11, 55), { roadId: '11', s: 5, roads: ['1', '11', '2'] });
    const backward = [
      { roadId: '2', laneId: -1, s: 30 },
      { roadId: '1', laneId: -1, s: 50 },
    ];
    assert.match(
      String(pointAlongRoute(parseOpenDrive(network([20, 25])), backward, 60)),
      /road 2 ends without a link in the driving direction of lane -1/,
    );
  });

  it('takes a way that equally near road ends elsewhere do not change, whichever esmini takes first', () => {
    // Road 1 into junction 9: connecting road 10 (20 m) leads to road 2, connecting road 12 (20 m) to road 3. The two
    // road ends after the junction are equally near, but only one leads to road 2: every order gives 1 > 10 > 2.
    const text = junctionNetwork([
      ['10', 20, '2'],
      ['12', 20, '3'],
    ]);
    const waypoints = [
      { roadId: '1', laneId: -1, s: 50 },
      { roadId: '2', laneId: -1, s: 30 },
    ];
    assert.deepEqual(pointAlongRoute(parseOpenDrive(text), waypoints, 55), { roadId: '10', s: 5, roads: ['1', '10', '2'] });
  });

  it("the lanes an entity drives along a route: its own lane, through lane sections (a link, or the same id as esmini keeps), into the route's roads", () => {
    // Road 1 of three lane sections: lane -2 links to nothing at 40 (esmini keeps the id), then becomes lane -1 at 70.
    const shoulder = '<lane id="-1" type="shoulder"><width sOffset="0" a="1" b="0" c="0" d="0"/></lane>';
    const sections = `<lanes>
      <laneSection s="0"><center><lane id="0" type="none"/></center>
        <right>${shoulder}<lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection>
      <laneSection s="40"><center><lane id="0" type="none"/></center>
        <right>${shoulder}<lane id="-2" type="driving"><link><successor id="-1"/></link><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection>
      <laneSection s="70"><center><lane id="0" type="none"/></center>
        <right><lane id="-1" type="driving"><link><predecessor id="-2"/><successor id="-1"/></link><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection>
    </lanes>`;
    const text = network([20, 25]).replace(/(<road id="1"[\s\S]*?)<lanes>[\s\S]*?<\/lanes>/, (_, before: string) => `${before}${sections}`);
    const roads = parseOpenDrive(text);
    const waypoints = [
      { roadId: '1', laneId: -2, s: 10 },
      { roadId: '2', laneId: -1, s: 30 },
    ];
    assert.deepEqual(routeLanes(roads, waypoints, { roadId: '1', laneId: -2, s: 20 }), [
      { roadId: '1', laneId: -2, from: 20, to: 40 },
      { roadId: '1', laneId: -2, from: 40, to: 70 },
      { roadId: '1', laneId: -1, from: 70, to: 100 },
      { roadId: '10', laneId: -1, from: 0, to: 20 },
      { roadId: '2', laneId: -1, from: 0, to: 30 },
    ]);
    // Off the route, against it, past its end: said, no lanes.
    assert.match(
      String(routeLanes(roads, waypoints, { roadId: '11', laneId: -1, s: 5 })),
      /lies on road 11, which the route does not run over \(1 > 10 > 2\)/,
    );
    assert.match(String(routeLanes(roads, waypoints, { roadId: '1', laneId: 1, s: 5 })), /lane 1 of road 1 drives against the route/);
    assert.match(
      String(routeLanes(roads, [waypoints[0], { roadId: '1', laneId: -2, s: 30 }], { roadId: '1', laneId: -2, s: 50 })),
      /lies past the route's last waypoint \(s 30\)/,
    );
    assert.match(
      String(routeLanes(roads, [waypoints[0], { roadId: '2', laneId: -1, s: 130 }], { roadId: '1', laneId: -2, s: 50 })),
      /\(s 130\) lies past the end of road 2 \(100 m\)/,
    );
  });

  it('a walker heads its own way, whichever way its lane is driven: its route planned from there, back through the junction (esmini RoadPath::Calculate reads the heading)', () => {
    const roads = parseOpenDrive(network([20, 25]));
    // On road 2's lane -1, heading against s: out of road 2's start, through the nearer connecting road backwards, into road 1.
    const start = { roadId: '2', laneId: -1, s: 50, direction: -1 as const };
    assert.deepEqual(routeLanes(roads, [start, { roadId: '1', laneId: -1, s: 60 }], start), [
      { roadId: '2', laneId: -1, from: 50, to: 0 },
      { roadId: '10', laneId: -1, from: 20, to: 0 },
      { roadId: '1', laneId: -1, from: 100, to: 60 },
    ]);
    // Heading out of road 1's start, which links to nothing.
    const back = { roadId: '1', laneId: -1, s: 50, direction: -1 as const };
    assert.match(
      String(routeLanes(roads, [back, { roadId: '2', laneId: -1, s: 30 }], back)),
      /road 1 ends without a link the way the entity heads/,
    );
  });

  it('places a point off the driving lanes (a walker on a sidewalk) in the nearest driving lane, as esmini snaps it, with the way it heads', () => {
    const sidewalk = '<lane id="-2" type="sidewalk"><width sOffset="0" a="2" b="0" c="0" d="0"/></lane>';
    const roads = parseOpenDrive(network([20, 25]).replace(/(<road id="1"[\s\S]*?<\/lane>)(<\/right>)/, `$1${sidewalk}$2`));
    // Road 1 runs along x from 0: lane -1 from y -3.5 to 0 (centre -1.75), its sidewalk from -5.5 to -3.5.
    const snapped = snappedLaneAtPoint(roads, 30, -4.5, Math.PI);
    assert.ok(typeof snapped !== 'string', String(snapped));
    assert.deepEqual(
      { ...snapped, s: Number(snapped.s.toFixed(6)), offset: Number(snapped.offset.toFixed(6)) },
      {
        roadId: '1',
        laneId: -1,
        s: 30,
        offset: -2.75,
        direction: -1,
      },
    );
    assert.equal((snappedLaneAtPoint(roads, 30, -4.5, 0.3) as { direction: number }).direction, 1);
    assert.match(String(snappedLaneAtPoint(roads, 30, -9, 0)), /x 30, y -9 lies on no road/);
  });
});
