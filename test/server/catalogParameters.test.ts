import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { Location, WorkspaceEdit } from 'vscode-languageserver/node';
import { fileUri, TestClient } from './harness';
import { applyEdits, inside, offsetOf } from '../support/textEdits';
import { temporaryWorkspace } from '../support/workspace';

/** A vehicle catalog entry that declares MaxSpeed and uses it. */
function vehicle(name: string, maxSpeed: number): string {
  return `    <Vehicle name="${name}" vehicleCategory="car">
      <ParameterDeclarations>
        <ParameterDeclaration name="MaxSpeed" parameterType="double" value="${maxSpeed}"/>
      </ParameterDeclarations>
      <Performance maxSpeed="$MaxSpeed" maxAcceleration="10" maxDeceleration="10"/>
      <Properties>
        <Property name="top" value="\${$MaxSpeed * 2}"/>
      </Properties>
    </Vehicle>
`;
}

const CATALOG = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" description="vehicles" author="test"/>
  <Catalog name="Vehicles">
${vehicle('CarA', 50)}${vehicle('CarB', 60)}  </Catalog>
</OpenSCENARIO>
`;

/** A scenario with a root MaxSpeed of its own (another scope) and one CatalogReference to `entry`. */
function scenario(entry: string, catalogs: string): string {
  return `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" description="uses ${entry}" author="test"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="MaxSpeed" parameterType="double" value="5"/>
  </ParameterDeclarations>
  <CatalogLocations>
    <VehicleCatalog>
      <Directory path="${catalogs}"/>
    </VehicleCatalog>
  </CatalogLocations>
  <RoadNetwork/>
  <Entities>
    <ScenarioObject name="Ego">
      <CatalogReference catalogName="Vehicles" entryName="${entry}">
        <ParameterAssignments>
          <ParameterAssignment parameterRef="MaxSpeed" value="$MaxSpeed"/>
        </ParameterAssignments>
      </CatalogReference>
    </ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
}

const FILES: Record<string, string> = {
  'catalogs/Vehicles.xosc': CATALOG,
  'first.xosc': scenario('CarA', 'catalogs'),
  'nested/second.xosc': scenario('CarA', '../catalogs'),
  'third.xosc': scenario('CarB', 'catalogs'),
};

/** `relative path:line:text` of each location, in the order given. */
function summarize(root: string, locations: Location[], texts: Record<string, string>): string[] {
  return locations.map((location) => {
    const relative = path.relative(root, new URL(location.uri).pathname);
    const text = texts[relative];
    const start = offsetOf(text, location.range.start);
    return `${relative}:${location.range.start.line + 1}:${text.slice(start, offsetOf(text, location.range.end))}`;
  });
}

describe('a catalog entry parameter across files: references and rename through ParameterAssignment (JSON-RPC)', function () {
  let root: string;
  let client: TestClient;
  const uriOf = (relative: string) => fileUri(path.join(root, relative));

  before(async function () {
    root = temporaryWorkspace(FILES);
    client = await TestClient.start({ root });
    await client.indexed();
    await client.openFile(path.join(root, 'catalogs/Vehicles.xosc'));
    await client.openFile(path.join(root, 'first.xosc'));
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  // Entry A's declaration, its two uses, and the assignments of first.xosc and nested/second.xosc.
  const expectedA = [
    'catalogs/Vehicles.xosc:7:MaxSpeed',
    'catalogs/Vehicles.xosc:9:MaxSpeed',
    'catalogs/Vehicles.xosc:11:MaxSpeed',
    'first.xosc:17:MaxSpeed',
    'nested/second.xosc:17:MaxSpeed',
  ];

  it("renames entry A's declaration, its uses and exactly the assignments that reach entry A", async function () {
    const at = client.at(uriOf('catalogs/Vehicles.xosc'), inside(CATALOG, 'name="MaxSpeed"', 8, 0));
    const prepared = await client.request<{ placeholder: string } | null>('textDocument/prepareRename', at);
    assert.equal(prepared?.placeholder, 'MaxSpeed');
    const edit = await client.request<WorkspaceEdit>('textDocument/rename', { ...at, newName: 'TopSpeed' });
    const changes = edit.changes ?? {};
    assert.deepEqual(
      Object.keys(changes).sort(),
      [uriOf('catalogs/Vehicles.xosc'), uriOf('first.xosc'), uriOf('nested/second.xosc')].sort(),
    );
    const catalog = applyEdits(CATALOG, changes[uriOf('catalogs/Vehicles.xosc')]);
    assert.equal(
      catalog,
      CATALOG.replace(
        vehicle('CarA', 50),
        vehicle('CarA', 50)
          .replace(/MaxSpeed"/g, 'TopSpeed"')
          .replace(/\$MaxSpeed/g, '$TopSpeed'),
      ),
    );
    assert.match(catalog, /<Vehicle name="CarB"[\s\S]*name="MaxSpeed"[\s\S]*maxSpeed="\$MaxSpeed"[\s\S]*\$\{\$MaxSpeed \* 2\}/);
    for (const file of ['first.xosc', 'nested/second.xosc']) {
      const renamed = applyEdits(FILES[file], changes[uriOf(file)]);
      // Only the assignment's parameterRef: the scenario's own MaxSpeed (another scope) and its use stay.
      assert.equal(renamed, FILES[file].replace('parameterRef="MaxSpeed"', 'parameterRef="TopSpeed"'), file);
    }
  });

  it("renames from an assignment's parameterRef the same set", async function () {
    const text = FILES['first.xosc'];
    const at = client.at(uriOf('first.xosc'), inside(text, 'parameterRef="MaxSpeed"', 16));
    const prepared = await client.request<{ placeholder: string } | null>('textDocument/prepareRename', at);
    assert.equal(prepared?.placeholder, 'MaxSpeed');
    const edit = await client.request<WorkspaceEdit>('textDocument/rename', { ...at, newName: 'TopSpeed' });
    const count = Object.values(edit.changes ?? {}).reduce((sum, edits) => sum + edits.length, 0);
    assert.equal(count, expectedA.length);
    assert.equal(
      applyEdits(text, edit.changes?.[uriOf('first.xosc')] ?? []),
      text.replace('parameterRef="MaxSpeed"', 'parameterRef="TopSpeed"'),
    );
    assert.equal(edit.changes?.[uriOf('third.xosc')], undefined);
  });

  it("lists the same references from an assignment and from the declaration, and entry B's apart", async function () {
    const fromAssignment = await client.request<Location[]>('textDocument/references', {
      ...client.at(uriOf('first.xosc'), inside(FILES['first.xosc'], 'parameterRef="MaxSpeed"', 16)),
      context: { includeDeclaration: true },
    });
    assert.deepEqual(summarize(root, fromAssignment, FILES), expectedA);
    const fromDeclaration = await client.request<Location[]>('textDocument/references', {
      ...client.at(uriOf('catalogs/Vehicles.xosc'), inside(CATALOG, 'name="MaxSpeed"', 8, 0)),
      context: { includeDeclaration: false },
    });
    assert.deepEqual(
      summarize(root, fromDeclaration, FILES),
      expectedA.filter((place) => place !== 'catalogs/Vehicles.xosc:7:MaxSpeed'),
    );
    const entryB = await client.request<Location[]>('textDocument/references', {
      ...client.at(uriOf('catalogs/Vehicles.xosc'), inside(CATALOG, 'name="MaxSpeed"', 8, 1)),
      context: { includeDeclaration: true },
    });
    assert.deepEqual(summarize(root, entryB, FILES), [
      'catalogs/Vehicles.xosc:16:MaxSpeed',
      'catalogs/Vehicles.xosc:18:MaxSpeed',
      'catalogs/Vehicles.xosc:20:MaxSpeed',
      'third.xosc:17:MaxSpeed',
    ]);
  });

  it("keeps the scenario's own MaxSpeed a one-file parameter", async function () {
    const text = FILES['first.xosc'];
    const edit = await client.request<WorkspaceEdit>('textDocument/rename', {
      ...client.at(uriOf('first.xosc'), inside(text, 'name="MaxSpeed"', 8)),
      newName: 'Limit',
    });
    assert.deepEqual(Object.keys(edit.changes ?? {}), [uriOf('first.xosc')]);
    assert.equal(
      applyEdits(text, edit.changes?.[uriOf('first.xosc')] ?? []),
      text.replace('name="MaxSpeed"', 'name="Limit"').replace('value="$MaxSpeed"', 'value="$Limit"'),
    );
  });
});

describe('a catalog entry parameter set from inside a .mosc package (JSON-RPC)', function () {
  let root: string;
  let client: TestClient;

  before(async function () {
    const zip = new JSZip();
    zip.file('main.xosc', scenario('CarA', 'catalogs'));
    zip.file('catalogs/Vehicles.xosc', CATALOG);
    root = temporaryWorkspace({
      'bundle.mosc': await zip.generateAsync({ type: 'uint8array' }),
      'catalogs/Vehicles.xosc': CATALOG,
      'first.xosc': scenario('CarA', 'catalogs'),
    });
    client = await TestClient.start({ root });
    await client.indexed();
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('finds the assignment inside the package and refuses a rename that would write into it', async function () {
    const packageCatalog = `mosc:${path.join(root, 'bundle.mosc')}/catalogs/Vehicles.xosc`;
    await client.open(packageCatalog, CATALOG);
    const at = client.at(packageCatalog, inside(CATALOG, 'name="MaxSpeed"', 8, 0));
    const references = await client.request<Location[]>('textDocument/references', { ...at, context: { includeDeclaration: true } });
    assert.deepEqual(
      references.map((location) => `${location.uri.slice(location.uri.lastIndexOf('bundle.mosc/'))}:${location.range.start.line + 1}`),
      [
        'bundle.mosc/catalogs/Vehicles.xosc:7',
        'bundle.mosc/catalogs/Vehicles.xosc:9',
        'bundle.mosc/catalogs/Vehicles.xosc:11',
        'bundle.mosc/main.xosc:17',
      ],
    );
    await assert.rejects(client.request('textDocument/rename', { ...at, newName: 'TopSpeed' }), /cannot write into packages/);
    // The catalog on disk is reached only by first.xosc, so its rename writes no package.
    const diskCatalog = await client.openFile(path.join(root, 'catalogs/Vehicles.xosc'));
    const edit = await client.request<WorkspaceEdit>('textDocument/rename', {
      ...client.at(diskCatalog, inside(CATALOG, 'name="MaxSpeed"', 8, 0)),
      newName: 'TopSpeed',
    });
    assert.deepEqual(Object.keys(edit.changes ?? {}).sort(), [diskCatalog, fileUri(path.join(root, 'first.xosc'))].sort());
    await client.close(packageCatalog);
  });
});
