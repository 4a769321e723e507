// Lint with type information, kept to rules that catch real bugs: promises nobody awaits, and
// editor imports leaking into the core (which the CLI and other editors use without VS Code).
import tseslint from 'typescript-eslint';

const editorModules = ['vscode', 'vscode-languageserver', 'vscode-languageserver/*', 'vscode-languageserver-*', 'vscode-languageclient', 'vscode-languageclient/*', 'vscode-jsonrpc', 'vscode-jsonrpc/*'];

export default tseslint.config(
  { ignores: ['dist/**', 'out/**', 'node_modules/**', '.cache/**', 'test-results/**', '**/*.js', '**/*.mjs', '**/*.cjs'] },
  {
    files: ['**/*.ts'],
    languageOptions: {
      parser: tseslint.parser,
      parserOptions: { projectService: true, tsconfigRootDir: import.meta.dirname },
    },
    plugins: { '@typescript-eslint': tseslint.plugin },
    linterOptions: { reportUnusedDisableDirectives: 'error' },
    rules: {
      '@typescript-eslint/no-floating-promises': 'error',
      '@typescript-eslint/no-misused-promises': ['error', { checksVoidReturn: { arguments: false } }],
      '@typescript-eslint/await-thenable': 'error',
    },
  },
  // One block per folder depth inside core: from core/a/b.ts, '../../x' leaves core while '../x' does not.
  ...[0, 1, 2, 3].map((depth) => ({
    files: [`server/src/core/${'*/'.repeat(depth)}*.ts`],
    rules: {
      'no-restricted-imports': [
        'error',
        {
          patterns: [
            { group: editorModules, message: 'server/src/core has no editor imports: it serves the CLI and every editor alike.' },
            { group: [`${'../'.repeat(depth + 1)}*`], message: 'server/src/core imports nothing outside core: dependencies point inward.' },
          ],
        },
      ],
    },
  })),
);
