import * as assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { parseXml, XmlElement } from '../../server/src/core/xml';
import { ExitCode } from '../../server/src/cli/common';
import { cliPath } from '../support/paths';
import { RULE_FILES } from '../support/qcRuleFiles';
import { BARE_XML_DECLARATION, fileHeader, openScenarioFile, vehicleObject } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

/**
 * The essential structure of the framework's result format (asam-ev/qc-framework
 * doc/schema/xqar_result_format.xsd, written down here rather than copied): for each element, the
 * children it may hold and the attributes it may carry. Levels are 1 error, 2 warning, 3 information
 * (doc/manual/file_formats.md); a Checker's status is completed, skipped or error.
 */
const XQAR: Record<string, { children: string[]; attributes: string[] }> = {
  CheckerResults: { children: ['CheckerBundle'], attributes: ['version'] },
  CheckerBundle: { children: ['Param', 'Checker'], attributes: ['build_date', 'description', 'name', 'summary', 'version'] },
  Param: { children: [], attributes: ['name', 'value'] },
  Checker: { children: ['Param', 'Issue', 'AddressedRule', 'Metadata'], attributes: ['checkerId', 'description', 'summary', 'status'] },
  Issue: { children: ['Locations', 'DomainSpecificInfo'], attributes: ['issueId', 'description', 'level', 'ruleUID'] },
  AddressedRule: { children: [], attributes: ['ruleUID'] },
  Locations: {
    children: ['FileLocation', 'XMLLocation', 'InertialLocation', 'TimeLocation', 'MessageLocation'],
    attributes: ['description'],
  },
  FileLocation: { children: [], attributes: ['column', 'row', 'offset'] },
  XMLLocation: { children: [], attributes: ['xpath'] },
};
/** A Checker's children come in this order (an xs:sequence); so do an Issue's. */
const SEQUENCES: Record<string, string[]> = {
  Checker: ['Param', 'Issue', 'AddressedRule', 'Metadata'],
  Issue: ['Locations', 'DomainSpecificInfo'],
};

function validateXqar(text: string): XmlElement {
  const document = parseXml(text);
  assert.deepEqual(
    document.problems.filter((problem) => problem.severity === 'error'),
    [],
  );
  const root = document.root;
  assert.equal(root?.name, 'CheckerResults');
  const visit = (element: XmlElement) => {
    const shape = XQAR[element.name];
    assert.ok(shape, `<${element.name}> is not an element of the result format`);
    for (const attr of element.attributes)
      assert.ok(shape.attributes.includes(attr.name), `${element.name}@${attr.name} is not in the result format`);
    const order = SEQUENCES[element.name];
    let last = -1;
    for (const child of element.children) {
      assert.ok(shape.children.includes(child.name), `<${child.name}> may not stand in <${element.name}>`);
      if (order) {
        assert.ok(order.indexOf(child.name) >= last, `<${child.name}> out of order in <${element.name}>`);
        last = order.indexOf(child.name);
      }
      visit(child);
    }
    if (element.name === 'Locations') assert.ok(element.children.length >= 1, 'a Locations holds at least one location');
    if (element.name === 'Issue') assert.match(attr(element, 'level'), /^[123]$/);
    if (element.name === 'Checker') assert.match(attr(element, 'status'), /^(completed|skipped|error)$/);
  };
  visit(root as XmlElement);
  return root as XmlElement;
}

function attr(element: XmlElement, name: string): string {
  return element.attributes.find((candidate) => candidate.name === name)?.value ?? '';
}

function all(element: XmlElement, name: string): XmlElement[] {
  return element.children.flatMap((child) => [...(child.name === name ? [child] : []), ...all(child, name)]);
}

/** A scenario with a signal the road file lacks and a negative light transition time, beside its road file. */
const ROAD = `<?xml version="1.0"?>
<OpenDRIVE><header revMajor="1" revMinor="6"/>
  <road id="1" length="100" junction="-1">
    <planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
    <lanes><laneSection s="0"><center><lane id="0" type="none"/></center></laneSection></lanes>
    <signals><signal id="101" s="50" t="-3"/></signals>
  </road>
</OpenDRIVE>
`;

const SCENARIO = openScenarioFile(
  `  <ParameterDeclarations/>
  <CatalogLocations/>
  <RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
  <Entities>
${vehicleObject('Ego')}  </Entities>
  <Storyboard>
    <Init><Actions><GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalStateAction name="999" state="off;on"/></TrafficSignalAction></InfrastructureAction></GlobalAction></Actions></Init>
    <Story name="S">
      <Act name="A">
        <ManeuverGroup name="G" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>
          <Maneuver name="M">
            <Event name="E" priority="override">
              <Action name="Light"><PrivateAction><AppearanceAction><LightStateAction transitionTime="-1"><LightType><VehicleLight vehicleLightType="headLights"/></LightType><LightState mode="on"/></LightStateAction></AppearanceAction></PrivateAction></Action>
              <StartTrigger/>
            </Event>
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger/>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
`,
  fileHeader({ description: 's', author: 't' }),
  BARE_XML_DECLARATION,
);

/** A configuration as the framework's runtime writes one (doc/manual/file_formats.md). */
function config(inputFile: string, checkers: string[] = [], resultFile = 'modular2simple.xqar'): string {
  return `<?xml version='1.0' encoding='UTF-8'?>
<Config>
    <Param name="InputFile" value="${inputFile}" />
    <CheckerBundle application="modular2simple">
        <Param name="resultFile" value="${resultFile}" />
${checkers.map((id) => `        <Checker checkerId="${id}" maxLevel="1" minLevel="3" />`).join('\n')}
    </CheckerBundle>
    <ReportModule application="TextReport">
        <Param name="strInputFile" value="Result.xqar" />
        <Param name="strReportFile" value="Report.txt" />
    </ReportModule>
</Config>
`;
}

/** Runs the bundle as the framework does: the manifest's exec_command through a shell, with the framework's variables set. */
function runAsFramework(root: string, configFile: string, outputDir: string): void {
  const manifest = JSON.parse(execFileSync(process.execPath, [cliPath, 'qc-bundle', '--manifest'], { encoding: 'utf8' })) as {
    module: { name: string; exec_type: string; module_type: string; exec_command: string }[];
  };
  assert.equal(manifest.module.length, 1);
  const [module] = manifest.module;
  assert.deepEqual([module.name, module.exec_type, module.module_type], ['modular2simple', 'executable', 'checker_bundle']);
  execFileSync('/bin/sh', ['-c', module.exec_command], {
    cwd: root,
    env: { ...process.env, ASAM_QC_FRAMEWORK_CONFIG_FILE: configFile, ASAM_QC_FRAMEWORK_OUTPUT_DIR: outputDir },
    encoding: 'utf8',
    stdio: 'pipe',
  });
}

describe('cli: qc-bundle (a checker bundle of the ASAM Quality Checker Framework)', () => {
  it('run by its manifest with a framework configuration, writes a result file of the framework format: each issue with its rule uid, level and locations', () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO, 'road.xodr': ROAD });
    fs.writeFileSync(path.join(root, 'config.xml'), config(path.join(root, 'scenario.xosc')));
    const outputDir = path.join(root, 'qc-output');
    runAsFramework(root, path.join(root, 'config.xml'), outputDir);
    const result = validateXqar(fs.readFileSync(path.join(outputDir, 'modular2simple.xqar'), 'utf8'));
    const [bundle] = result.children;
    assert.equal(attr(bundle, 'name'), 'modular2simple');
    assert.ok(bundle.children.some((child) => child.name === 'Param' && attr(child, 'name') === 'InputFile'));
    const issues = all(result, 'Issue');
    const signal = issues.find(
      (issue) => attr(issue, 'ruleUID') === 'asam.net:xosc:1.2.0:reference_control.resolvable_signal_id_in_traffic_signal_state_action',
    );
    assert.ok(signal, issues.map((issue) => attr(issue, 'ruleUID')).join('\n'));
    assert.equal(attr(signal, 'level'), '1');
    assert.equal(
      attr(all(signal, 'XMLLocation')[0], 'xpath'),
      '/OpenSCENARIO/Storyboard/Init/Actions/GlobalAction/InfrastructureAction/TrafficSignalAction/TrafficSignalStateAction',
    );
    assert.equal(
      attr(all(signal, 'FileLocation')[0], 'row'),
      String(SCENARIO.split('\n').findIndex((line) => line.includes('name="999"')) + 1),
    );
    const light = issues.find(
      (issue) => attr(issue, 'ruleUID') === 'asam.net:xosc:1.2.0:data_type.non_negative_transition_time_in_light_state_action',
    );
    assert.ok(light);
    // Each checker addresses its rule; issue ids are unique.
    for (const checker of all(result, 'Checker')) assert.equal(all(checker, 'AddressedRule').length, 1);
    assert.equal(new Set(issues.map((issue) => attr(issue, 'issueId'))).size, issues.length);
  });

  it("names the rule of each issue as the editor does: the FileHeader's version is its own checker (xml.version_is_defined), its date valid_schema", () => {
    const root = temporaryWorkspace(RULE_FILES);
    fs.writeFileSync(path.join(root, 'config.xml'), config('version.xosc'));
    execFileSync(process.execPath, [cliPath, 'qc-bundle', 'config.xml'], { cwd: root, stdio: 'pipe' });
    const result = validateXqar(fs.readFileSync(path.join(root, 'modular2simple.xqar'), 'utf8'));
    const addressed = (checkerId: string) => {
      const checker = all(result, 'Checker').find((element) => attr(element, 'checkerId') === checkerId);
      assert.ok(
        checker,
        all(result, 'Checker')
          .map((element) => attr(element, 'checkerId'))
          .join('\n'),
      );
      return { rule: attr(all(checker, 'AddressedRule')[0], 'ruleUID'), issues: all(checker, 'Issue').length };
    };
    assert.deepEqual(addressed('check_modular2simple_xml_version_is_defined'), {
      rule: 'asam.net:xosc:1.0.0:xml.version_is_defined',
      issues: 2,
    });
    assert.deepEqual(addressed('check_modular2simple_xml_valid_schema'), { rule: 'asam.net:xosc:1.0.0:xml.valid_schema', issues: 1 });
  });

  it("reports only the checkers a configuration names, into the configuration's resultFile; the configuration alone as argument works too", () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO, 'road.xodr': ROAD });
    const checker = 'check_modular2simple_data_type_non_negative_transition_time_in_light_state_action';
    fs.writeFileSync(path.join(root, 'config.xml'), config('scenario.xosc', [checker], 'light.xqar'));
    execFileSync(process.execPath, [cliPath, 'qc-bundle', 'config.xml'], { cwd: root, stdio: 'pipe' });
    const result = validateXqar(fs.readFileSync(path.join(root, 'light.xqar'), 'utf8'));
    assert.deepEqual(
      all(result, 'Checker').map((element) => attr(element, 'checkerId')),
      [checker],
    );
    assert.equal(all(result, 'Issue').length, 1);
  });

  it('a configuration it cannot run from is a loud failure, and no result file is written', () => {
    const root = temporaryWorkspace({
      'config.xml': '<Config><CheckerBundle application="modular2simple"/></Config>',
      'bad.xml': '<NotAConfig/>',
    });
    for (const file of ['config.xml', 'bad.xml']) {
      assert.throws(
        () => execFileSync(process.execPath, [cliPath, 'qc-bundle', '-c', file, '-o', 'out'], { cwd: root, stdio: 'pipe' }),
        (error: { status: number; stderr: Buffer }) =>
          error.status === 1 && /InputFile|not a Quality Checker/.test(error.stderr.toString()),
      );
    }
    assert.ok(!fs.existsSync(path.join(root, 'out')));
  });

  it('a result file it cannot write is exit 3 (an output error, as for every command), saying nothing was changed', () => {
    const root = temporaryWorkspace({ 'main.xosc': SCENARIO, 'config.xml': config('main.xosc'), blocker: 'a file, not a folder' });
    // The output folder cannot be made (a file stands in its path), or the result's name is taken by a folder.
    fs.mkdirSync(path.join(root, 'taken', 'modular2simple.xqar'), { recursive: true });
    for (const outputDir of [path.join('blocker', 'out'), 'taken']) {
      assert.throws(
        () => execFileSync(process.execPath, [cliPath, 'qc-bundle', '-c', 'config.xml', '-o', outputDir], { cwd: root, stdio: 'pipe' }),
        (error: { status: number; stderr: Buffer }) =>
          error.status === ExitCode.io &&
          /modular2simple\.xqar: error: cannot write the output \(.*\); nothing was changed/.test(error.stderr.toString()),
      );
    }
    assert.equal(fs.readFileSync(path.join(root, 'blocker'), 'utf8'), 'a file, not a folder');
    assert.deepEqual(fs.readdirSync(path.join(root, 'taken', 'modular2simple.xqar')), []);
  });
});
