import * as path from 'node:path';
import { pathToFileURL } from 'node:url';
import { Problem, Severity } from '../core/problems';
import { ruleOf } from '../core/rules';
import { SourceRef } from '../core/sources';
import { VERSION } from './common';

/**
 * `check --format sarif`: SARIF 2.1.0 (OASIS), the log format GitHub code scanning and other CI
 * dashboards read. A file inside a package is its own artifact whose `parentIndex` is the package.
 */
export interface SarifLog {
  $schema: string;
  version: '2.1.0';
  runs: SarifRun[];
}

interface SarifRun {
  tool: { driver: { name: string; version: string; rules: SarifRule[] } };
  originalUriBaseIds: Record<string, { uri: string }>;
  artifacts: SarifArtifact[];
  results: SarifResult[];
  columnKind: 'utf16CodeUnits';
}

interface SarifRule {
  id: string;
  name: string;
  shortDescription: { text: string };
  helpUri?: string;
  defaultConfiguration: { level: SarifLevel };
  properties: { codes: string[]; asamQualityCheckerRule?: string };
}

interface SarifArtifact {
  location: SarifArtifactLocation;
  parentIndex?: number;
}

interface SarifArtifactLocation {
  uri: string;
  uriBaseId?: string;
  index?: number;
}

interface SarifPhysicalLocation {
  artifactLocation: SarifArtifactLocation;
  region: { startLine: number; startColumn: number; endLine: number; endColumn: number };
}

interface SarifResult {
  ruleId: string;
  ruleIndex: number;
  level: SarifLevel;
  message: { text: string };
  locations: { physicalLocation: SarifPhysicalLocation }[];
  relatedLocations?: { id: number; physicalLocation: SarifPhysicalLocation; message: { text: string } }[];
  properties: { code: string };
}

type SarifLevel = 'error' | 'warning' | 'note';

const SARIF_SCHEMA = 'https://json.schemastore.org/sarif-2.1.0.json';
const SOURCE_ROOT = 'SRCROOT';

function levelOf(severity: Severity): SarifLevel {
  return severity === 'error' ? 'error' : severity === 'warning' ? 'warning' : 'note';
}

/** Relative URI references are percent-encoded per segment, so a space or `#` in a name survives. */
function relativeUri(relative: string): string {
  return relative.split(path.sep).map(encodeURIComponent).join('/');
}

/** The log of one check: every problem, its rule, its file (relative to `workingDirectory` where it lies below it). */
export function sarifLog(problems: readonly Problem[], workingDirectory: string): SarifLog {
  const rules: SarifRule[] = [];
  const ruleIndex = new Map<string, number>();
  const artifacts: SarifArtifact[] = [];
  const artifactIndex = new Map<string, number>();

  const diskLocation = (disk: string): SarifArtifactLocation => {
    const relative = path.relative(workingDirectory, disk);
    return relative && !relative.startsWith('..') && !path.isAbsolute(relative)
      ? { uri: relativeUri(relative), uriBaseId: SOURCE_ROOT }
      : { uri: pathToFileURL(disk).href };
  };

  const artifactOf = (ref: SourceRef): SarifArtifactLocation => {
    let parent: number | undefined;
    let location = diskLocation(ref.disk);
    let key = ref.disk;
    for (let depth = 0; depth <= ref.entries.length; depth++) {
      if (depth > 0) {
        key += `\u0000${ref.entries[depth - 1]}`;
        location = { uri: relativeUri(ref.entries[depth - 1]) };
      }
      let index = artifactIndex.get(key);
      if (index === undefined) {
        index = artifacts.length;
        artifacts.push(parent === undefined ? { location } : { location, parentIndex: parent });
        artifactIndex.set(key, index);
      }
      parent = index;
    }
    return { ...artifacts[parent as number].location, index: parent };
  };

  const physical = (ref: SourceRef, range: Problem['range']): SarifPhysicalLocation => ({
    artifactLocation: artifactOf(ref),
    region: {
      startLine: range.start.line + 1,
      startColumn: range.start.character + 1,
      endLine: range.end.line + 1,
      endColumn: range.end.character + 1,
    },
  });

  const results = problems.map((problem): SarifResult => {
    const rule = ruleOf(problem);
    const ruleId = rule.id;
    let index = ruleIndex.get(ruleId);
    if (index === undefined) {
      index = rules.length;
      const { qcRule, helpUri } = rule;
      rules.push({
        id: ruleId,
        name: qcRule ? (ruleId.split(':').pop() ?? ruleId) : problem.code,
        shortDescription: { text: rule.description },
        ...(helpUri ? { helpUri } : {}),
        defaultConfiguration: { level: levelOf(problem.severity) },
        properties: { codes: [problem.code], ...(qcRule ? { asamQualityCheckerRule: qcRule } : {}) },
      });
      ruleIndex.set(ruleId, index);
    } else if (!rules[index].properties.codes.includes(problem.code)) {
      rules[index].properties.codes.push(problem.code);
    }
    const text = problem.hint ? `${problem.message} (${problem.hint})` : problem.message;
    return {
      ruleId,
      ruleIndex: index,
      level: levelOf(problem.severity),
      message: { text },
      locations: [{ physicalLocation: physical(problem.source, problem.range) }],
      ...(problem.related?.length
        ? {
            relatedLocations: problem.related.map((item, id) => ({
              id,
              physicalLocation: physical(item.source, item.range),
              message: { text: item.message },
            })),
          }
        : {}),
      properties: { code: problem.code },
    };
  });

  return {
    $schema: SARIF_SCHEMA,
    version: '2.1.0',
    runs: [
      {
        tool: { driver: { name: 'modular2simple', version: VERSION, rules } },
        originalUriBaseIds: { [SOURCE_ROOT]: { uri: pathToFileURL(workingDirectory + path.sep).href } },
        artifacts,
        results,
        columnKind: 'utf16CodeUnits',
      },
    ],
  };
}
