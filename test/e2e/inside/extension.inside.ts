import * as assert from 'node:assert/strict';
import * as vscode from 'vscode';
import type { Modular2SimpleApi } from '../../../client/src/extension';
import { INSIDE_TESTS, type InsideTestKey } from '../titles';
import { editingTests } from './editing.inside';
import { esminiTests } from './esmini.inside';
import { screenshot } from './harnessClient';
import { EXTENSION_ID, type InsideTests, TEST_MS, waitFor } from './helpers';
import { languageFeatureTests } from './languageFeatures.inside';
import { newScenarioTests } from './newScenario.inside';
import { packAndFlattenTests } from './packAndFlatten.inside';
import { packageTests } from './packages.inside';
import { previewTests } from './preview.inside';
import { refactoringTests } from './refactorings.inside';
import { ruleTests } from './rules.inside';
import { structureTests } from './structure.inside';
import { distributionTests } from './distributions.inside';
import { carlaTests } from './carla.inside';
import { debuggingTests } from './debugging.inside';
import { birdsEyeDebugTests } from './birdsEyeDebug.inside';
import { libraryTests } from './library.inside';

const TESTS: InsideTests = {
  ...editingTests,
  ...packageTests,
  ...languageFeatureTests,
  ...previewTests,
  ...packAndFlattenTests,
  ...structureTests,
  ...esminiTests,
  ...newScenarioTests,
  ...distributionTests,
  ...refactoringTests,
  ...ruleTests,
  ...carlaTests,
  ...debuggingTests,
  ...birdsEyeDebugTests,
  ...libraryTests,
};

/**
 * The order the tests run in, one VS Code and one workspace for all: a test sees what earlier ones left
 * (structure saves main.xosc with CutInVehicle renamed, renameInPackage renames HardBrake in braking.mosc
 * and main.xosc), so the order is kept as it is.
 */
const ORDER: InsideTestKey[] = [
  'activates',
  'grammar',
  'typing',
  'packageView',
  'packageEdit',
  'brokenPackage',
  'diagnostic',
  'windowSwitch',
  'completion',
  'definition',
  'preview',
  'scenarioPath',
  'roadPath',
  'catalogDirectory',
  'pack',
  'flatten',
  'expression',
  'insidePackage',
  'structure',
  'renameInPackage',
  'runEsmini',
  'runEsminiClean',
  'runEsminiCutIn',
  'runEsminiAnyway',
  'packUnsaved',
  'flattenAnyway',
  'structureFollows',
  'schemaCompletion',
  'schemaDeprecated',
  'ruleCodes',
  'newScenario',
  'distributionLens',
  'extractToSimple',
  'carlaExport',
  'carlaCheck',
  'carlaSettingsAtOnce',
  'carlaRun',
  'debugScenario',
  'debugImportLine',
  'debugBirdsEyeTurns',
  'libraryCompose',
  'libraryComposeFromNew',
  'libraryInsertHere',
  'libraryDrop',
  'libraryDropAsks',
  'debugTimeline',
  'debugTimelineSession',
];

/** The extension's tests inside VS Code, each feature's in its own file; the bird's-eye view's follow (birdsEye.inside.ts). */
export function defineExtensionTests(): void {
  describe('Modular2Simple in a real VS Code', function () {
    this.timeout(TEST_MS);

    before(async function () {
      this.timeout(TEST_MS);
      const extension = vscode.extensions.getExtension<Modular2SimpleApi>(EXTENSION_ID);
      assert.ok(extension, `${EXTENSION_ID} is not installed`);
      await waitFor('the extension to activate', () => extension.isActive);
      await extension.exports.serverReady;
    });

    beforeEach(async () => {
      await vscode.commands.executeCommand('notifications.clearAll');
    });

    afterEach(async function () {
      await screenshot(`${this.currentTest?.state === 'failed' ? 'FAILED ' : ''}${this.currentTest?.title ?? 'unnamed'}`).catch(
        () => undefined,
      );
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    });

    for (const key of ORDER) {
      const test = TESTS[key];
      assert.ok(test, `no test for ${key}`);
      it(INSIDE_TESTS[key], test);
    }
  });
}
