import * as assert from 'node:assert/strict';
import { expressionMessage } from '../../server/src/core/diagnostics/expressionWords';
import * as path from 'node:path';
import {
  analyzeDocument,
  CatalogLoader,
  catalogEntryFor,
  catalogReferenceAt,
  declarationAt,
  DocumentSemantics,
  entryParameterValue,
  parameterUseAt,
  parametersInScopeAt,
  referencesOf,
  scopeAt,
  semanticProblems,
  valueAt,
} from '../../server/src/core/semantics';
import JSZip from 'jszip';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { temporaryWorkspace } from '../support/workspace';
import { BARE_XML_DECLARATION, fileHeader, openScenarioFile } from '../support/fixtures';

const CATALOG = openScenarioFile(
  `  <Catalog name="VehicleCatalog">
    <Vehicle name="car" vehicleCategory="car">
      <ParameterDeclarations>
        <ParameterDeclaration name="Speed" parameterType="double" value="10"/>
        <ParameterDeclaration name="Half" parameterType="double" value="\${$Speed / 2}"/>
      </ParameterDeclarations>
      <Performance maxSpeed="$Half" maxAcceleration="$Speed" maxDeceleration="10"/>
    </Vehicle>
  </Catalog>
`,
  fileHeader({ description: 'c', author: 't' }),
  BARE_XML_DECLARATION,
);

/** Speed is declared at the root, shadowed in Story S1 and again in its Maneuver M1; Story S2 sees the root's. */
const SCENARIO = openScenarioFile(
  `  <ParameterDeclarations>
    <ParameterDeclaration name="Speed" parameterType="double" value="20"/>
    <ParameterDeclaration name="Twice" parameterType="double" value="\${2 * $Speed}"/>
    <ParameterDeclaration name="Count" parameterType="int" value="\${7 / 2}"/>
    <ParameterDeclaration name="Owner" parameterType="string" value="Ego"/>
    <ParameterDeclaration name="Idle" parameterType="double" value="1"/>
    <ParameterDeclaration name="Owner" parameterType="string" value="Other"/>
  </ParameterDeclarations>
  <VariableDeclarations>
    <VariableDeclaration name="Counter" variableType="int" value="0"/>
  </VariableDeclarations>
  <CatalogLocations>
    <VehicleCatalog>
      <Directory path="catalogs"/>
    </VehicleCatalog>
  </CatalogLocations>
  <Entities>
    <ScenarioObject name="Ego">
      <CatalogReference catalogName="VehicleCatalog" entryName="car">
        <ParameterAssignments>
          <ParameterAssignment parameterRef="Speed" value="$Twice"/>
          <ParameterAssignment parameterRef="Sped" value="1"/>
        </ParameterAssignments>
      </CatalogReference>
    </ScenarioObject>
    <ScenarioObject name="Car">
      <CatalogReference catalogName="VehicleCatalog" entryName="truck"/>
    </ScenarioObject>
    <ScenarioObject name="Bike">
      <CatalogReference catalogName="BikeCatalog" entryName="bike"/>
    </ScenarioObject>
    <ScenarioObject name="Truck">
      <Vehicle name="truck" vehicleCategory="truck">
        <ParameterDeclarations>
          <ParameterDeclaration name="Speed" parameterType="double" value="25"/>
        </ParameterDeclarations>
        <Performance maxSpeed="$Speed" maxAcceleration="3" maxDeceleration="8"/>
      </Vehicle>
    </ScenarioObject>
  </Entities>
  <Storyboard>
    <Story name="S1">
      <ParameterDeclarations>
        <ParameterDeclaration name="Speed" parameterType="double" value="\${$Speed + 1}"/>
      </ParameterDeclarations>
      <Act name="A1">
        <ManeuverGroup name="G1" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="$Owner"/></Actors>
          <Maneuver name="M1">
            <ParameterDeclarations>
              <ParameterDeclaration name="Speed" parameterType="double" value="5"/>
            </ParameterDeclarations>
            <Event name="E1" priority="overwrite">
              <Action name="InManeuver"><AbsoluteTargetSpeed value="$Speed"/></Action>
            </Event>
          </Maneuver>
          <Maneuver name="M2">
            <Event name="E2" priority="overwrite">
              <Action name="InStory"><AbsoluteTargetSpeed value="\${$Speed * 2}"/></Action>
              <Action name="Broken"><AbsoluteTargetSpeed value="\${$Speed / ($Speed - 21)}"/></Action>
              <Action name="Unknown"><AbsoluteTargetSpeed value="$Missing"/></Action>
              <Action name="Ghost"><EntityRef entityRef="Nobody"/><VariableAction variableRef="Countr"/></Action>
              <StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>
                <StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="E1" state="endTransition"/>
                <StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="E9" state="endTransition"/>
              </ByValueCondition></Condition></ConditionGroup></StartTrigger>
            </Event>
          </Maneuver>
        </ManeuverGroup>
      </Act>
    </Story>
    <Story name="S2">
      <Act name="A2">
        <ManeuverGroup name="G2" maximumExecutionCount="1">
          <Maneuver name="M3">
            <Event name="E3" priority="overwrite">
              <Action name="AtRoot"><AbsoluteTargetSpeed value="$Speed"/></Action>
            </Event>
          </Maneuver>
        </ManeuverGroup>
      </Act>
    </Story>
  </Storyboard>
`,
  fileHeader({ description: 's', author: 't' }),
  BARE_XML_DECLARATION,
);

async function analyze(): Promise<DocumentSemantics> {
  const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO, 'catalogs/VehicleCatalog.xosc': CATALOG });
  const ref = diskRef(path.join(root, 'scenario.xosc'));
  return analyzeDocument(ref, parseXml(SCENARIO), new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })), false);
}

/** The offset of the `occurrence`-th match of `needle` (inside it by `shift`). */
function at(needle: string, shift = 0, occurrence = 0): number {
  let index = -1;
  for (let i = 0; i <= occurrence; i++) index = SCENARIO.indexOf(needle, index + 1);
  assert.ok(index >= 0, needle);
  return index + shift;
}

describe('semantics: scopes, values and catalogs', () => {
  let semantics: DocumentSemantics;
  before(async () => {
    semantics = await analyze();
  });

  it('builds the scope tree: root, Story S1, its Maneuver M1 (and the Story and Maneuver without declarations share their parent scope)', () => {
    const root = semantics.model.root;
    assert.ok(root);
    assert.equal(root.element.name, 'OpenSCENARIO');
    assert.deepEqual(
      root.declarations.map((declaration) => declaration.name),
      ['Speed', 'Twice', 'Count', 'Owner', 'Idle', 'Owner'],
    );
    assert.deepEqual(
      root.children.map((scope) => scope.element.name),
      ['Vehicle', 'Story'],
    );
    assert.deepEqual(
      root.children[1].children.map((scope) => scope.element.name),
      ['Maneuver'],
    );
    assert.equal(scopeAt(semantics, at('$Speed"/></Action>'))?.element.name, 'Maneuver');
    assert.equal(scopeAt(semantics, at('AtRoot'))?.element.name, 'OpenSCENARIO');
  });

  it('resolves $Speed to the innermost declaration: Maneuver, then Story, then root', () => {
    const inManeuver = declarationAt(semantics, at('InManeuver"><AbsoluteTargetSpeed value="$Speed', 45));
    assert.equal(inManeuver?.scope.element.name, 'Maneuver');
    const inStory = declarationAt(semantics, at('InStory"><AbsoluteTargetSpeed value="${$Speed', 44));
    assert.equal(inStory?.scope.element.name, 'Story');
    const atRoot = declarationAt(semantics, at('AtRoot"><AbsoluteTargetSpeed value="$Speed', 41));
    assert.equal(atRoot?.scope.element.name, 'OpenSCENARIO');
    // The Story's own value `${$Speed + 1}` sees the root's Speed, not itself.
    const storyValue = parameterUseAt(semantics, at('value="${$Speed + 1}', 10));
    assert.equal(storyValue?.declaration?.scope.element.name, 'OpenSCENARIO');
    // An entity declared inline shadows the root too.
    const inVehicle = declarationAt(semantics, at('maxSpeed="$Speed"', 11));
    assert.equal(inVehicle?.scope.element.name, 'Vehicle');
    assert.equal(
      semantics.evaluator.declarationValue(inVehicle!).ok && (semantics.evaluator.declarationValue(inVehicle!) as { value: number }).value,
      25,
    );
  });

  it('lists the references of each declaration and never mixes scopes', () => {
    const root = semantics.model.root!.byName.get('Speed')!;
    assert.deepEqual(
      referencesOf(semantics, root).map((use) => use.element.name),
      ['ParameterDeclaration', 'ParameterDeclaration', 'AbsoluteTargetSpeed'],
      'Twice, the Story Speed, and AtRoot',
    );
    const story = semantics.model.root!.children[1].byName.get('Speed')!;
    assert.deepEqual(
      referencesOf(semantics, story).map((use) => use.attribute.value),
      ['${$Speed * 2}', '${$Speed / ($Speed - 21)}', '${$Speed / ($Speed - 21)}'],
      'InStory and Broken, nothing of M1 or S2',
    );
    assert.equal(declarationAt(semantics, at('name="Twice"', 7))?.name, 'Twice');
  });

  it('evaluates values with their type and provenance', () => {
    const twice = semantics.evaluator.declarationValue(semantics.model.root!.byName.get('Twice')!);
    assert.deepEqual([twice.ok && twice.value, twice.ok && twice.type], [40, 'double']);
    const count = semantics.evaluator.declarationValue(semantics.model.root!.byName.get('Count')!);
    // SPEC 12 (issue 17): the standard converts a double to an int only when it has no fraction, so 3.5 is an error.
    assert.ok(!count.ok && /3\.5 is not integral/.test(expressionMessage(count.errors[0])), 'an int does not take 3.5');
    const inStory = valueAt(semantics, at('${$Speed * 2}', 2));
    assert.ok(inStory?.result.ok);
    assert.equal(inStory.result.value, 42, '(20 + 1) * 2');
    const inManeuver = valueAt(semantics, at('InManeuver"><AbsoluteTargetSpeed value="$Speed', 45));
    assert.ok(inManeuver?.result.ok && inManeuver.result.provenance.kind === 'declaration');
    assert.equal(inManeuver.result.value, 5);
    assert.equal(inManeuver.result.provenance.declaration.scope.element.name, 'Maneuver');
    assert.deepEqual(valueAt(semantics, at('name="S2"', 7))?.result, {
      ok: true,
      value: 'S2',
      type: 'string',
      provenance: { kind: 'literal' },
    });
  });

  it('offers the parameters in scope, innermost first, shadowed ones left out', () => {
    const inManeuver = parametersInScopeAt(semantics, at('InManeuver'));
    assert.deepEqual(
      inManeuver.map((entry) => `${entry.declaration.name}@${entry.declaration.scope.element.name}`),
      ['Speed@Maneuver', 'Twice@OpenSCENARIO', 'Count@OpenSCENARIO', 'Owner@OpenSCENARIO', 'Idle@OpenSCENARIO'],
    );
    const inTwice = parametersInScopeAt(semantics, at('name="Twice"'));
    assert.deepEqual(
      inTwice.map((entry) => entry.declaration.name),
      ['Speed'],
      'a value sees only the earlier declarations',
    );
  });

  it('resolves catalog references and evaluates an entry with the reference assignments', () => {
    const reference = catalogReferenceAt(semantics, at('entryName="car"'));
    assert.ok(reference?.entry);
    assert.equal(reference.entry.name, 'car');
    assert.equal(catalogEntryFor(semantics, reference.reference.element), reference);
    const entryModel = reference.entry.file.model;
    // Inside the catalog entry, its own declarations are found (the file has no other scope to shadow).
    assert.ok(entryModel.uses.length === 3 && entryModel.uses.every((use) => use.declaration?.scope.element === reference.entry?.element));
    const speed = entryModel.scopes[1].byName.get('Speed')!;
    const half = entryModel.scopes[1].byName.get('Half')!;
    const assigned = entryParameterValue(semantics, reference, speed);
    assert.ok(assigned.ok && assigned.provenance.kind === 'assignment');
    assert.equal(assigned.value, 40, '$Twice of the referencing file');
    const derived = entryParameterValue(semantics, reference, half);
    assert.equal(derived.ok && derived.value, 20, 'the default ${$Speed / 2} with the assigned Speed');
  });

  it('reports each problem of the checks list with its code and range', () => {
    const found = semanticProblems(semantics).map((problem) => {
      const lines = SCENARIO.split('\n');
      const text = lines[problem.range.start.line].slice(problem.range.start.character, problem.range.end.character);
      return `${problem.code}:${problem.severity}:${text}`;
    });
    assert.deepEqual(found.sort(), [
      'division-by-zero:error:($Speed - 21)',
      'duplicate-parameter:warning:Owner',
      'type-mismatch:error:${7 / 2}',
      'undeclared-entity:error:Nobody',
      'undeclared-parameter:error:$Missing',
      'undeclared-variable:error:Countr',
      'unknown-assigned-parameter:error:Sped',
      'unknown-catalog-entry:error:truck',
      'unknown-catalog:error:BikeCatalog',
      'unknown-storyboard-element:warning:E9',
      'unused-parameter:hint:Count',
      'unused-parameter:hint:Idle',
    ]);
  });
});

describe('semantics: catalogs inside packages, through SCENARIO_PATH, and from unsaved text', () => {
  it('finds the catalogs of a main.xosc inside a .mosc in the package', async () => {
    const zip = new JSZip();
    zip.file('main.xosc', SCENARIO);
    zip.file('catalogs/VehicleCatalog.xosc', CATALOG);
    const root = temporaryWorkspace({ 'scenario.mosc': await zip.generateAsync({ type: 'uint8array' }) });
    const store = new ScenarioStore({ scenarioPath: [], root });
    const main = childRef(diskRef(path.join(root, 'scenario.mosc')), 'main.xosc');
    const semantics = await analyzeDocument(main, parseXml(SCENARIO), new CatalogLoader(store), false);
    const car = semantics.catalogs.references.find((reference) => reference.entryName === 'car');
    assert.equal(car?.entry?.file.ref.entries.join('/'), 'catalogs/VehicleCatalog.xosc');
  });

  it('finds a catalog directory that does not exist beside the file through SCENARIO_PATH, as esmini does with --path', async () => {
    const root = temporaryWorkspace({ 'scenarios/scenario.xosc': SCENARIO, 'shared/catalogs/VehicleCatalog.xosc': CATALOG });
    const store = new ScenarioStore({ scenarioPath: [path.join(root, 'shared')], root });
    const semantics = await analyzeDocument(
      diskRef(path.join(root, 'scenarios', 'scenario.xosc')),
      parseXml(SCENARIO),
      new CatalogLoader(store),
      false,
    );
    assert.equal(semantics.catalogs.locations[0].directories[0].via, 'scenarioPath');
    assert.ok(semantics.catalogs.references.find((reference) => reference.entryName === 'car')?.entry);
  });

  it("reads a catalog file from the editor's unsaved text", async () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO, 'catalogs/VehicleCatalog.xosc': CATALOG });
    const store = new ScenarioStore({ scenarioPath: [], root });
    store.setOverlay(
      diskRef(path.join(root, 'catalogs', 'VehicleCatalog.xosc')),
      CATALOG.replace('<Vehicle name="car"', '<Vehicle name="truck"'),
    );
    const semantics = await analyzeDocument(diskRef(path.join(root, 'scenario.xosc')), parseXml(SCENARIO), new CatalogLoader(store), false);
    const codes = semanticProblems(semantics).map((problem) => `${problem.code}:${problem.message}`);
    assert.ok(
      codes.some((code) =>
        code.startsWith(
          `unknown-catalog-entry:catalog 'VehicleCatalog' (${path.join(root, 'catalogs', 'VehicleCatalog.xosc')}) has no entry named 'car'`,
        ),
      ),
      codes.join('\n'),
    );
    assert.ok(
      codes.some((code) => code.endsWith('it has: truck')),
      'truck exists in the unsaved text',
    );
  });
});
