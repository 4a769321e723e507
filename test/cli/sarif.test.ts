import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import Ajv from 'ajv-draft-04';
import JSZip from 'jszip';
import { outerGroup, runCli, scenario, simpleGroup } from '../support/fixtures';
import { repoRoot, requireCorpus, sharedDir } from '../support/paths';
import { EXPECTED_RULES, qcRuleHref, RULE_FILES } from '../support/qcRuleFiles';
import { temporaryWorkspace } from '../support/workspace';

/** The OASIS SARIF 2.1.0 schema (JSON Schema draft 04), kept in the fixtures with its source (NOTICE.md there): never downloaded at test time. */
const sarifSchema = JSON.parse(
  fs.readFileSync(path.join(repoRoot, 'test', 'fixtures', 'sarif', 'sarif-2.1.0-rtm.5.json'), 'utf8'),
) as object;

interface Region {
  startLine: number;
  startColumn: number;
}
interface Location {
  artifactLocation: { uri: string; uriBaseId?: string; index: number };
  region: Region;
}
interface Log {
  runs: {
    tool: { driver: { rules: { id: string; shortDescription: { text: string }; helpUri?: string; properties: { codes: string[] } }[] } };
    artifacts: { location: { uri: string }; parentIndex?: number }[];
    results: {
      ruleId: string;
      ruleIndex: number;
      level: string;
      message: { text: string };
      locations: { physicalLocation: Location }[];
      relatedLocations?: unknown[];
    }[];
  }[];
}

function validate(log: unknown): void {
  const ajv = new Ajv({ strict: false, allErrors: true, unicodeRegExp: false }); // the schema's language pattern is not valid with the u flag;
  // The formats the schema names, checked as the URL parser and Date read them.
  ajv.addFormat('uri', (text: string) => URL.canParse(text));
  ajv.addFormat('uri-reference', (text: string) => URL.canParse(text, 'file:///base/'));
  ajv.addFormat('date-time', (text: string) => !Number.isNaN(Date.parse(text)));
  const valid = ajv.validate(sarifSchema, log);
  assert.ok(valid, JSON.stringify(ajv.errors, null, 2));
}

describe('cli: check --format sarif', () => {
  it('writes a SARIF 2.1.0 log valid against the OASIS schema: rules with descriptions, results with rule, level, file and region', async () => {
    const broken = scenario(
      outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters: [['AbsoluteTargetSped.value', '9']] }] }]),
    );
    const zip = new JSZip();
    zip.file('main.xosc', scenario(outerGroup('Car', 'nobody', [{ file: 'missing.xosc', groups: [{ name: 'Go', parameters: [] }] }])));
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': broken,
      'package.mosc': await zip.generateAsync({ type: 'uint8array' }),
      'not xml.xosc': '<OpenSCENARIO><FileHeader',
    });
    const run = runCli(['check', '.', '--format', 'sarif'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    const log = JSON.parse(run.stdout) as Log;
    validate(log);
    const [only] = log.runs;
    const rules = only.tool.driver.rules;
    assert.equal(new Set(rules.map((rule) => rule.id)).size, rules.length, 'each rule once');
    for (const result of only.results) {
      assert.equal(rules[result.ruleIndex].id, result.ruleId);
      assert.ok(rules[result.ruleIndex].shortDescription.text.length > 0);
    }

    const unknownKey = only.results.find((result) => result.ruleId === 'modular2simple:unknown-key');
    assert.ok(unknownKey, JSON.stringify(only.results.map((result) => result.ruleId)));
    assert.equal(unknownKey.level, 'error');
    const keyLocation = unknownKey.locations[0].physicalLocation;
    assert.deepEqual(keyLocation.artifactLocation.uri, 'main.xosc');
    assert.equal(keyLocation.artifactLocation.uriBaseId, 'SRCROOT');
    const keyLine = broken.split('\n').findIndex((line) => line.includes('AbsoluteTargetSped')) + 1;
    assert.equal(keyLocation.region.startLine, keyLine);

    const xml = only.results.find((result) => result.ruleId === 'asam.net:xosc:1.0.0:xml.valid_xml_document');
    assert.ok(xml, 'malformed XML names the ASAM Quality Checker rule');
    assert.match(
      String(rules[xml.ruleIndex].helpUri),
      /checker_bundle_doc\.md#check_asam_xosc_xml_valid_xml_document$/,
      'and links to its description',
    );
    assert.equal(xml.locations[0].physicalLocation.artifactLocation.uri, 'not%20xml.xosc');

    const inPackage = only.results.find(
      (result) => only.artifacts[result.locations[0].physicalLocation.artifactLocation.index].parentIndex !== undefined,
    );
    assert.ok(inPackage, 'a problem inside a package is located in the package entry');
    const entry = only.artifacts[inPackage.locations[0].physicalLocation.artifactLocation.index];
    assert.equal(entry.location.uri, 'main.xosc');
    assert.equal(only.artifacts[entry.parentIndex as number].location.uri, 'package.mosc');
  });

  it('the real corpus (101 OpenSCENARIO files) gives a valid log whose every result names a described rule', function () {
    requireCorpus(this);
    const shared = fs.realpathSync(sharedDir);
    const run = runCli(['check', path.join(shared, 'corpus', 'openscenario'), '--format', 'sarif'], { cwd: shared });
    const log = JSON.parse(run.stdout) as Log;
    validate(log);
    const rules = log.runs[0].tool.driver.rules;
    for (const result of log.runs[0].results) assert.ok(rules[result.ruleIndex].shortDescription.text, result.ruleId);
    assert.ok(
      log.runs[0].artifacts.every((artifact) => !artifact.location.uri.startsWith('file:')),
      'files below the working folder are relative to SRCROOT',
    );
  });

  it('a clean check is a valid log with no results and exit 0', () => {
    const root = temporaryWorkspace({ 'simple.xosc': scenario(simpleGroup('Go')) });
    const run = runCli(['check', 'simple.xosc', '--format', 'sarif', '--schema-version', 'off'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const log = JSON.parse(run.stdout) as Log;
    validate(log);
    assert.deepEqual(log.runs[0].results, []);
  });

  it('text, json and sarif count the same notes (information and hints): the text summary no longer leaves them out', () => {
    // An unused parameter (a hint), and a 0.9 FileHeader where the fixture states a version (a note: checked against 1.0).
    const text = scenario(simpleGroup('Go'))
      .replace(/revMajor="1" revMinor="\d"/, 'revMajor="0" revMinor="9"')
      .replace(
        '<Entities>',
        '<ParameterDeclarations><ParameterDeclaration name="unused" parameterType="double" value="1"/></ParameterDeclarations>\n  <Entities>',
      );
    const root = temporaryWorkspace({ 'old.xosc': text });
    const json = JSON.parse(runCli(['check', 'old.xosc', '--format', 'json'], { cwd: root }).stdout) as {
      errors: number;
      warnings: number;
      notes: number;
      problems: { severity: string }[];
    };
    const notes = json.problems.filter((problem) => problem.severity === 'information' || problem.severity === 'hint').length;
    assert.ok(notes >= 1, JSON.stringify(json.problems));
    assert.equal(json.notes, notes);
    const sarif = JSON.parse(runCli(['check', 'old.xosc', '--format', 'sarif'], { cwd: root }).stdout) as Log;
    assert.equal(sarif.runs[0].results.filter((result) => result.level === 'note').length, notes);
    const summary = runCli(['check', 'old.xosc'], { cwd: root }).stderr.trim().split('\n').pop() ?? '';
    assert.match(summary, new RegExp(`^checked 1 file: ${json.errors} errors?, ${json.warnings} warnings?, ${notes} notes? \\(`));
  });

  it("check --format json names each problem's rule; stats refuses sarif", () => {
    const root = temporaryWorkspace({ 'main.xosc': '<OpenSCENARIO>' });
    const run = runCli(['check', 'main.xosc', '--format', 'json'], { cwd: root });
    const report = JSON.parse(run.stdout) as { problems: { code: string; rule: string }[] };
    assert.equal(report.problems[0].code, 'xml');
    assert.equal(report.problems[0].rule, 'asam.net:xosc:1.0.0:xml.valid_xml_document');
    const stats = runCli(['stats', '.', '--format', 'sarif'], { cwd: root });
    assert.equal(stats.status, 2);
    assert.match(stats.stderr, /stats writes text or json/);
  });

  it('json and sarif name the rule of each problem as the editor does: a more specific QC rule where the problem has one', () => {
    const root = temporaryWorkspace(RULE_FILES);
    const json = runCli(['check', '.', '--format', 'json'], { cwd: root, schema: true });
    const report = JSON.parse(json.stdout) as { problems: { file: string; code: string; rule: string }[] };
    const named = new Set(report.problems.map((problem) => `${problem.file} ${problem.code} ${problem.rule}`));
    for (const [file, code, qcRule] of EXPECTED_RULES) {
      const line = `${file} ${code} ${qcRule ?? `modular2simple:${code}`}`;
      assert.ok(named.has(line), `${line} not in\n${[...named].join('\n')}`);
    }
    const sarif = runCli(['check', '.', '--format', 'sarif'], { cwd: root, schema: true });
    const log = JSON.parse(sarif.stdout) as Log;
    validate(log);
    const [only] = log.runs;
    const rootTag = 'asam.net:xosc:1.0.0:xml.root_tag_is_openscenario';
    const result = only.results.find((candidate) => candidate.ruleId === rootTag);
    assert.ok(result, only.results.map((candidate) => candidate.ruleId).join('\n'));
    const rule = only.tool.driver.rules[result.ruleIndex];
    assert.equal(rule.helpUri, qcRuleHref(rootTag));
    assert.deepEqual(rule.properties.codes, ['schema-unknown-element']);
    const schema = only.tool.driver.rules.find((candidate) => candidate.id === 'asam.net:xosc:1.0.0:xml.valid_schema');
    assert.ok(schema?.properties.codes.includes('schema-value'), 'the FileHeader date is valid_schema');
  });
});
