/*
 * A real library modularized in memory and flattened back, for the corpus test and bench/modularizeLibraries.ts:
 * the figures each prints (lines before and after, SPEC 9; how many mains flatten back equivalent, SPEC 8).
 */
import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { firstDifference } from '../../server/src/core/equivalence';
import { Flattener } from '../../server/src/core/flatten';
import { buildModel } from '../../server/src/core/model';
import { memoryHost, modularize, ModularizeInput, ModularizeResult, notAPlainScenario } from '../../server/src/core/modularize';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { repoRoot, sharedDir } from './paths';

/** A library to measure: its name and its scenario files. */
export interface RealLibrary {
  name: string;
  files: string[];
}

export interface LibraryFigures {
  name: string;
  /** Plain scenarios among the files (catalogs and distributions are left alone). */
  scenarios: number;
  linesBefore: number;
  linesAfter: number;
  reduction: number;
  /** Mains whose flattening, by the project's flattener, is equivalent to their input (SPEC 8). */
  equivalent: number;
  /** Mains whose flattening warns that a parameter's value differs from its simple scenario's (parameter-conflict). */
  conflicted: number;
  simpleScenarios: number;
  keptInline: ModularizeResult['keptInline'];
  /** Lines inside ManeuverGroups: all that extracting groups can ever take out of the mains. */
  groupLines: number;
}

/** Every .xosc below a folder, sorted. */
function xoscBelow(folder: string): string[] {
  if (!fs.existsSync(folder)) return [];
  return fs
    .readdirSync(folder, { recursive: true, encoding: 'utf8' })
    .filter((name) => name.toLowerCase().endsWith('.xosc'))
    .map((name) => path.join(folder, name))
    .sort();
}

/** Only the files directly in a folder. */
function xoscIn(folder: string): string[] {
  return xoscBelow(folder).filter((file) => path.dirname(file) === folder);
}

/**
 * The libraries on this machine: the corpus in ../shared, and the public test-protocol libraries when a
 * checkout of them is in M2S_REAL_LIBRARIES (default .cache/real-libraries): `ncap/` holding
 * vectorgrp/OSC-NCAP-scenarios, `alks/` holding asam-oss/OSC-ALKS-scenarios, `asam/` holding the folders
 * exampleFilesVersion1_2 and exampleFilesVersion1_3 of RA-Consulting-GmbH/openscenario.api.test
 * (cpp/applications/openScenarioTester/res/, ASAM's examples). Absent ones are named in `missing`.
 */
export function realLibraries(): { libraries: RealLibrary[]; missing: string[] } {
  const corpus = path.join(sharedDir, 'corpus');
  const real = process.env.M2S_REAL_LIBRARIES ?? path.join(repoRoot, '.cache', 'real-libraries');
  const ncap = path.join(real, 'ncap', 'OpenSCENARIO', 'NCAP');
  const candidates: RealLibrary[] = [
    {
      name: "the paper's library (31 result.xosc)",
      files: fs.existsSync(path.join(corpus, 'modular2simple', 'library'))
        ? fs
            .readdirSync(path.join(corpus, 'modular2simple', 'library'))
            .map((folder) => path.join(corpus, 'modular2simple', 'library', folder, 'result.xosc'))
            .filter((file) => fs.existsSync(file))
            .sort()
        : [],
    },
    { name: "esmini's examples", files: xoscBelow(path.join(corpus, 'openscenario', 'esmini')) },
    { name: "ScenarioRunner's examples", files: xoscBelow(path.join(corpus, 'openscenario', 'scenario_runner')) },
    {
      name: 'Euro NCAP test protocols (OSC-NCAP-scenarios, 23)',
      files: ['AEB_C2C_2023', 'AEB_VRU_2023', 'CA-FC_2026'].flatMap((folder) => xoscIn(path.join(ncap, folder))),
    },
    {
      name: 'ALKS templates (OSC-ALKS-scenarios, 15)',
      files: xoscIn(path.join(real, 'alks', 'logical_scenarios', 'concrete_scenarios')),
    },
    {
      name: "ASAM's 1.2 and 1.3 examples (openscenario.api.test)",
      files: ['exampleFilesVersion1_2', 'exampleFilesVersion1_3'].flatMap((folder) => xoscIn(path.join(real, 'asam', folder))),
    },
  ];
  return {
    libraries: candidates.filter((library) => library.files.length > 0),
    missing: candidates.filter((library) => library.files.length === 0).map((library) => library.name),
  };
}

/**
 * Modularizes a library in memory (each main in its input's place, the simple scenarios in a `simple`
 * folder beside them, nothing written) and flattens every main again with a flattener of its own.
 */
export async function modularizeLibrary(library: RealLibrary): Promise<{ figures: LibraryFigures; result: ModularizeResult }> {
  const inputs = library.files
    .map((file) => ({ path: file, output: file, text: fs.readFileSync(file, 'utf8') }))
    .filter((input) => notAPlainScenario(input.text) === undefined);
  let common = path.dirname(inputs[0].path);
  for (const input of inputs) while (!input.path.startsWith(common + path.sep)) common = path.dirname(common);
  const result = await modularize(inputs, { simpleFolder: path.join(common, 'simple') });

  const files = new Map<string, string>();
  for (const behaviour of result.behaviours) files.set(behaviour.file, behaviour.text);
  for (const main of result.mains) files.set(main.output, main.text);
  const flattener = new Flattener(new ScenarioStore({ host: memoryHost(files), scenarioPath: [] }));
  const asWritten = new Flattener(new ScenarioStore({ scenarioPath: [] }));
  let equivalent = 0;
  let conflicted = 0;
  let groupLines = 0;
  for (const [index, main] of result.mains.entries()) {
    // An input with errors of its own (a catalog folder its source did not ship) is compared as forced, as its main is.
    const input = await asWritten.analyze(diskRef(inputs[index].path));
    const force = input.problems.some((problem) => problem.severity === 'error');
    const flattened = await flattener.flatten(diskRef(main.output), { outputPath: main.output, force });
    if (flattened.text !== undefined && firstDifference(flattened.text, inputs[index].text) === undefined) equivalent++;
    if (flattened.problems.some((problem) => problem.code === 'parameter-conflict')) conflicted++;
    const document = parseXml(inputs[index].text);
    for (const group of buildModel(document).groups)
      groupLines += document.text.slice(group.element.start, group.element.end).split('\n').length;
  }
  return {
    result,
    figures: {
      name: library.name,
      scenarios: inputs.length,
      linesBefore: result.totals.linesBefore,
      linesAfter: result.totals.linesAfter,
      reduction: result.totals.reduction,
      equivalent,
      conflicted,
      simpleScenarios: result.behaviours.length,
      keptInline: result.keptInline,
      groupLines,
    },
  };
}

/** One line of figures: lines before and after, the share saved, the mains equivalent, the ceiling. */
export function figuresLine(figures: LibraryFigures): string {
  const n = (value: number) => value.toLocaleString('en-US');
  return `${figures.name}: ${figures.scenarios} scenarios, ${n(figures.linesBefore)} -> ${n(figures.linesAfter)} lines (${figures.reduction} % saved), ${figures.equivalent}/${figures.scenarios} flatten back equivalent (${figures.conflicted} warned of a parameter conflict), ${figures.simpleScenarios} simple scenarios, ${figures.keptInline.length} recurring groups left inline; ${Math.round((figures.groupLines / Math.max(1, figures.linesBefore)) * 1000) / 10} % of the lines are inside ManeuverGroups`;
}

/** Each main flattened again from memory (catalogs from the disk), compared with its input, and warned of no parameter conflict. */
export async function assertFlattensBack(inputs: ModularizeInput[], result: ModularizeResult): Promise<void> {
  assert.deepEqual(result.failures, []);
  const files = new Map<string, string>();
  for (const behaviour of result.behaviours) files.set(behaviour.file, behaviour.text);
  for (const main of result.mains) files.set(main.output, main.text);
  const flattener = new Flattener(new ScenarioStore({ host: memoryHost(files), scenarioPath: [] }));
  for (const [index, main] of result.mains.entries()) {
    const flattened = await flattener.flatten(diskRef(main.output), { outputPath: main.output });
    assert.ok(flattened.text !== undefined, `${main.output}: ${flattened.problems.map((problem) => problem.message).join('; ')}`);
    assert.equal(firstDifference(flattened.text, inputs[index].text), undefined, main.output);
    // A main whose declaration differs from its simple scenario's would be warned (parameter-conflict).
    assert.deepEqual(
      flattened.problems.filter((problem) => problem.code === 'parameter-conflict').map((problem) => problem.message),
      [],
      main.output,
    );
  }
}
