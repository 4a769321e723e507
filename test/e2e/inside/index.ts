import Mocha from 'mocha';
import { HARNESS_ENV } from '../titles';
import { post } from './harnessClient';
import { TEST_MS } from './helpers';
import { defineBirdsEyeTests } from './birdsEye.inside';
import { defineExtensionTests } from './extension.inside';
import { defineVariationsTests } from './variations.inside';

/** Entry point that VS Code calls in the extension host (extensionTestsPath). */
export async function run(): Promise<void> {
  const grep = process.env[HARNESS_ENV.grep];
  const mocha = new Mocha({ ui: 'bdd', timeout: TEST_MS, color: false, reporter: 'spec', ...(grep ? { grep } : {}) });
  mocha.suite.emit('pre-require', globalThis, 'extension.inside', mocha);
  defineExtensionTests();
  defineBirdsEyeTests();
  defineVariationsTests();
  const pending: Promise<unknown>[] = [];
  const failures = await new Promise<number>((resolve) => {
    const runner = mocha.run((count) => resolve(count));
    const report = (test: Mocha.Test, state: 'passed' | 'failed' | 'pending', error?: Error): void => {
      pending.push(
        post('/result', {
          title: test.title,
          state,
          durationMs: test.duration ?? 0,
          error: error ? `${error.message}\n${error.stack ?? ''}` : undefined,
        }).catch(() => undefined),
      );
    };
    runner.on('pass', (test) => report(test, 'passed'));
    runner.on('fail', (test, error: Error) => report(test as Mocha.Test, 'failed', error));
    runner.on('pending', (test) => report(test, 'pending'));
  });
  await Promise.all(pending);
  // The page's codeAutomationExit may not reach the harness once the host winds down under load: say it first.
  await post('/finished', { failures }).catch(() => undefined);
  if (failures > 0) throw new Error(`${failures} test(s) failed inside VS Code`);
}
