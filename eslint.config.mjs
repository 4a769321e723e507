// Lint with type information, kept to rules that catch real bugs: promises nobody awaits, and imports
// against the layering: editor imports leaking into the core (which the CLI and other editors use without
// VS Code), the client reaching into the server instead of common/src, features calling handlers.
import tseslint from 'typescript-eslint';

const editorModules = [
  'vscode',
  'vscode-languageserver',
  'vscode-languageserver/*',
  'vscode-languageserver-*',
  'vscode-languageclient',
  'vscode-languageclient/*',
  'vscode-jsonrpc',
  'vscode-jsonrpc/*',
];

export default tseslint.config(
  // JavaScript is linted where it is type-checked (test/tsconfig.json's checkJs): the benchmarks and the scripts.
  {
    ignores: [
      'dist/**',
      'out/**',
      'node_modules/**',
      '.cache/**',
      'test-results/**',
      '**/*.js',
      '**/*.mjs',
      '**/*.cjs',
      '!bench/*.mjs',
      '!bench/*.cjs',
      '!scripts/*.mjs',
    ],
  },
  {
    files: ['**/*.ts', 'bench/*.mjs', 'bench/*.cjs', 'scripts/*.mjs'],
    languageOptions: {
      parser: tseslint.parser,
      parserOptions: {
        // The scripts with a declaration file of their own (.d.mts) are left out of test/tsconfig.json's program by it.
        projectService: { allowDefaultProject: ['scripts/esminiBuild.mjs', 'scripts/startSettings.mjs', 'scripts/cli-code-cache.mjs'] },
        tsconfigRootDir: import.meta.dirname,
      },
    },
    plugins: { '@typescript-eslint': tseslint.plugin },
    linterOptions: { reportUnusedDisableDirectives: 'error' },
    rules: {
      '@typescript-eslint/no-floating-promises': 'error',
      '@typescript-eslint/no-misused-promises': ['error', { checksVoidReturn: { arguments: false } }],
      '@typescript-eslint/await-thenable': 'error',
    },
  },
  // One block per folder depth inside core: from core/a/b.ts, '../../x' leaves core while '../x' does not;
  // common/src (two folders further up) is the one place outside core it may import from.
  ...[0, 1, 2, 3].map((depth) => ({
    files: [`server/src/core/${'*/'.repeat(depth)}*.ts`],
    rules: {
      'no-restricted-imports': [
        'error',
        {
          patterns: [
            { group: editorModules, message: 'server/src/core has no editor imports: it serves the CLI and every editor alike.' },
            {
              regex: `^(?!(\\.\\./){${depth + 3}}common/src/)(\\.\\./){${depth + 1}}`,
              message: 'server/src/core imports only core and common/src: dependencies point inward.',
            },
          ],
        },
      ],
    },
  })),
  // What client and server share depends on neither, nor on an editor; the protocol files may use the LSP's
  // own message types (vscode-languageserver-protocol), which both sides speak.
  {
    files: ['common/src/**/*.ts'],
    rules: { 'no-restricted-imports': ['error', { patterns: commonPatterns(editorModules) }] },
  },
  {
    files: ['common/src/protocol.ts', 'common/src/sceneProtocol.ts', 'common/src/libraryProtocol.ts'],
    rules: {
      'no-restricted-imports': ['error', { patterns: commonPatterns([...editorModules, '!vscode-languageserver-protocol']) }],
    },
  },
  {
    files: ['client/src/**/*.ts'],
    rules: { 'no-restricted-imports': ['error', { patterns: [clientOutOfServer('^(\\.\\./)+server/')] }] },
  },
  // Handlers call features, never the other way round.
  {
    files: ['server/src/features/**/*.ts'],
    rules: {
      'no-restricted-imports': [
        'error',
        {
          patterns: [
            { regex: '^\\.\\.?/(.*/)?handlers(/|$)', message: 'server/src/features do not import handlers: handlers call features.' },
          ],
        },
      ],
    },
  },
);

function commonPatterns(editors) {
  return [
    { group: editors, message: 'common/src has no editor imports: client, server and the CLI share it.' },
    { regex: '^(\\.\\./)+(server|client)/', message: 'common/src imports nothing from the server or the client: both import it.' },
  ];
}

function clientOutOfServer(regex) {
  return { regex, message: 'client/src imports nothing from server/: what it shares with the server lives in common/src.' };
}
