import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { besideOutputWritable, FILE_PATH_ELEMENTS, filePathSites, Flattener, rebasePaths } from '../../server/src/core/flatten';
import { applyEdits } from '../../server/src/core/flatten/edits';
import { elementParticles, schemaFor, SCHEMA_VERSIONS } from '../../server/src/core/schema/model';
import { diskRef, nodeFileSystem, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { packageOf } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

const SCENARIO = (declarations: string, body: string) => `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-01-01T00:00:00" description="paths" author="m2s"/>
  <ParameterDeclarations>${declarations}</ParameterDeclarations>
${body}
</OpenSCENARIO>
`;

const BODY = `  <CatalogLocations>
    <VehicleCatalog>
      <Directory path="../catalogs/Vehicles/"/>
    </VehicleCatalog>
    <ControllerCatalog>
      <Directory path="NoSuchFolder"/>
    </ControllerCatalog>
  </CatalogLocations>
  <RoadNetwork>
    <LogicFile filepath="../xodr/road.xodr"/>
    <SceneGraphFile filepath="Town05"/>
  </RoadNetwork>`;

/** ws/xosc/scenario.xosc beside ws/xodr/road.xodr and ws/catalogs/Vehicles. */
function workspace(): string {
  return temporaryWorkspace({
    'xodr/road.xodr': '<OpenDRIVE/>',
    'catalogs/Vehicles/cars.xosc': '<OpenSCENARIO/>',
    'xosc/scenario.xosc': '',
  });
}

async function rebased(text: string, base: string, outputDirectory: string | undefined) {
  const document = parseXml(text);
  const result = await rebasePaths({ document, baseOf: () => base, outputDirectory, kindOf: (diskPath) => nodeFileSystem.kind(diskPath) });
  return { ...result, text: applyEdits(text, result.edits) };
}

describe('core: rebasing the file paths of an output (SPEC 11.6)', () => {
  it('knows every element the ASAM schemas 1.0 to 1.3 type as File or Directory, by its parent', () => {
    const known = new Set(FILE_PATH_ELEMENTS.map((entry) => `${entry.parent}/${entry.element}`));
    for (const version of SCHEMA_VERSIONS) {
      const schema = schemaFor(version);
      // The element names each complex type is used under, to name the parents as documents write them.
      const elementNamesOfType = new Map<string, Set<string>>();
      for (const type of Object.values(schema.complexTypes)) {
        for (const particle of elementParticles(type.content)) {
          if (!elementNamesOfType.has(particle.type)) elementNamesOfType.set(particle.type, new Set());
          elementNamesOfType.get(particle.type)?.add(particle.name);
        }
      }
      for (const [typeName, type] of Object.entries(schema.complexTypes)) {
        for (const particle of elementParticles(type.content)) {
          if (particle.type !== 'File' && particle.type !== 'Directory') continue;
          for (const parent of elementNamesOfType.get(typeName) ?? [])
            assert.ok(known.has(`${parent}/${particle.name}`), `${version}: ${parent}/${particle.name} (${particle.type})`);
        }
      }
      assert.deepEqual(
        schema.complexTypes.File.attributes.map((attribute) => attribute.name),
        ['filepath'],
      );
      assert.deepEqual(
        schema.complexTypes.Directory.attributes.map((attribute) => attribute.name),
        ['path'],
      );
    }
  });

  it('finds the paths of a document in order, and nothing under another parent', () => {
    const text = SCENARIO(
      '',
      BODY + '\n  <Entities><ScenarioObject name="x"><File filepath="not-a-path-site"/></ScenarioObject></Entities>',
    );
    const sites = filePathSites(parseXml(text).root);
    assert.deepEqual(
      sites.map((site) => `${site.element.name}=${site.attribute.value}`),
      ['Directory=../catalogs/Vehicles/', 'Directory=NoSuchFolder', 'LogicFile=../xodr/road.xodr', 'SceneGraphFile=Town05'],
    );
  });

  it('changes nothing for an output beside its source', async () => {
    const root = workspace();
    const text = SCENARIO('', BODY);
    const result = await rebased(text, path.join(root, 'xosc'), path.join(root, 'xosc'));
    assert.deepEqual(result.edits, []);
    assert.equal(result.text, text);
    assert.equal(result.resolved.length, 2);
  });

  it('rewrites what resolves for another folder, keeps a trailing slash, leaves what does not resolve (Town05) as written', async () => {
    const root = workspace();
    const result = await rebased(SCENARIO('', BODY), path.join(root, 'xosc'), path.join(root, 'out', 'deeper'));
    assert.match(result.text, /<Directory path="\.\.\/\.\.\/catalogs\/Vehicles\/"\/>/);
    assert.match(result.text, /<Directory path="NoSuchFolder"\/>/);
    assert.match(result.text, /<LogicFile filepath="\.\.\/\.\.\/xodr\/road\.xodr"\/>/);
    assert.match(result.text, /<SceneGraphFile filepath="Town05"\/>/);
    assert.deepEqual(
      result.unresolved.map((site) => site.attribute.value),
      ['NoSuchFolder', 'Town05'],
    );
    const up = await rebased(SCENARIO('', BODY), path.join(root, 'xosc'), path.dirname(root));
    assert.match(up.text, new RegExp(`<LogicFile filepath="${path.basename(root)}/xodr/road\\.xodr"/>`));
  });

  it('writes absolute paths for standard output, and leaves absolute paths as written', async () => {
    const root = workspace();
    const result = await rebased(SCENARIO('', BODY), path.join(root, 'xosc'), undefined);
    assert.ok(result.text.includes(`<LogicFile filepath="${path.join(root, 'xodr', 'road.xodr')}"/>`));
    const again = await rebased(result.text, path.join(root, 'xosc'), path.join(root, 'elsewhere'));
    assert.deepEqual(
      again.edits.filter((edit) => edit.text.includes('road.xodr')),
      [],
    );
  });

  it('leaves a path naming a parameter as written, warning when its value is a relative path that resolves', async () => {
    const root = workspace();
    const declarations =
      '<ParameterDeclaration name="Road" parameterType="string" value="../xodr/road.xodr"/><ParameterDeclaration name="Town" parameterType="string" value="Town05"/>';
    const body = '  <RoadNetwork>\n    <LogicFile filepath="$Road"/>\n    <SceneGraphFile filepath="$Town"/>\n  </RoadNetwork>';
    const moved = await rebased(SCENARIO(declarations, body), path.join(root, 'xosc'), path.join(root, 'out'));
    assert.deepEqual(moved.edits, []);
    assert.equal(moved.findings.length, 1);
    assert.match(moved.findings[0].message, /'\$Road' gives the relative path '\.\.\/xodr\/road\.xodr'.*left as written/);
    const beside = await rebased(SCENARIO(declarations, body), path.join(root, 'xosc'), path.join(root, 'xosc'));
    assert.deepEqual(beside.findings, []);
  });
});

describe('core: Flattener.flatten rebases for its output (SPEC 11.6)', () => {
  const main = (road: string) =>
    SCENARIO(
      '<ParameterDeclaration name="Road" parameterType="string" value="../xodr/road.xodr"/>',
      `  <RoadNetwork>\n    <LogicFile filepath="${road}"/>\n  </RoadNetwork>\n  <Storyboard/>`,
    );

  it("rewrites the main file's own paths for another folder, and warns at the main file's line about a path naming a parameter", async () => {
    const root = workspace();
    fs.writeFileSync(path.join(root, 'xosc', 'plain.xosc'), main('../xodr/road.xodr'));
    fs.writeFileSync(path.join(root, 'xosc', 'parameter.xosc'), main('$Road'));
    const flattener = new Flattener(new ScenarioStore({ scenarioPath: [], root }));
    const plain = await flattener.flatten(diskRef(path.join(root, 'xosc', 'plain.xosc')), {
      outputPath: path.join(root, 'out', 'deeper', 'plain.xosc'),
    });
    assert.match(plain.text ?? '', /<LogicFile filepath="\.\.\/\.\.\/xodr\/road\.xodr"\/>/);
    const parameter = await flattener.flatten(diskRef(path.join(root, 'xosc', 'parameter.xosc')), {
      outputPath: path.join(root, 'out', 'deeper', 'parameter.xosc'),
    });
    assert.match(parameter.text ?? '', /<LogicFile filepath="\$Road"\/>/);
    const warning = parameter.problems.find((problem) => problem.code === 'file-path');
    assert.ok(warning, JSON.stringify(parameter.problems));
    assert.equal(warning.severity, 'warning');
    assert.equal(warning.source.disk, path.join(root, 'xosc', 'parameter.xosc'));
    assert.equal(warning.range.start.line, 5, 'the LogicFile line of parameter.xosc');
    const beside = await flattener.flatten(diskRef(path.join(root, 'xosc', 'parameter.xosc')));
    assert.equal(beside.problems.filter((problem) => problem.code === 'file-path').length, 0);
  });

  it("keeps a $parameter path naming a file of the main's package as written and puts its copy where the value names it from the output", async () => {
    const root = workspace();
    const scenario = main('$Road').replace('value="../xodr/road.xodr"', 'value="roads/packed.xodr"');
    fs.writeFileSync(path.join(root, 'p.mosc'), await packageOf({ 'main.xosc': scenario, 'roads/packed.xodr': '<OpenDRIVE packed="1"/>' }));
    const flattener = new Flattener(new ScenarioStore({ scenarioPath: [], root }));
    const ref = { disk: path.join(root, 'p.mosc'), entries: ['main.xosc'] };
    const written = await flattener.flatten(ref, { outputPath: path.join(root, 'out', 'flat.xosc') });
    assert.match(written.text ?? '', /<LogicFile filepath="\$Road"\/>/);
    assert.deepEqual(
      written.files.map((file) => [file.path, Buffer.from(file.bytes).toString('utf8'), file.namedBy]),
      [[path.join(root, 'out', 'roads', 'packed.xodr'), '<OpenDRIVE packed="1"/>', '$Road']],
    );
    assert.deepEqual(written.problems, []);
    const printed = await flattener.flatten(ref, { standardOutput: true });
    assert.deepEqual(printed.files, []);
    assert.match(
      printed.problems.map((problem) => problem.message).join('\n'),
      /'\$Road' names roads\/packed\.xodr inside the package, which standard output cannot carry/,
    );
    // A writer never replaces another file lying where the copy goes: the warning names that file; the same bytes are fine.
    fs.mkdirSync(path.join(root, 'out', 'roads'), { recursive: true });
    fs.writeFileSync(path.join(root, 'out', 'roads', 'packed.xodr'), '<OpenDRIVE other="1"/>');
    const taken = await besideOutputWritable(written.files, nodeFileSystem);
    assert.deepEqual(taken.files, []);
    assert.match(
      taken.warnings.join('\n'),
      /'\$Road' names a file of the package, whose copy would go to .*packed\.xodr, which holds another file/,
    );
    fs.writeFileSync(path.join(root, 'out', 'roads', 'packed.xodr'), '<OpenDRIVE packed="1"/>');
    assert.deepEqual(await besideOutputWritable(written.files, nodeFileSystem), { files: written.files, warnings: [] });
  });
});
