/** The tests that run inside VS Code; the outer mocha test asserts that each of them ran and passed. */
export const INSIDE_TESTS = {
  activates: 'opening the example workspace activates the extension',
  grammar: 'the grammar gives the modular elements and parameterAttributes their own scopes',
  typing: 'typing an opening tag closes it, and Ctrl+/ comments a line out',
  packageView: 'opening a .mosc shows the files inside it',
  packageEdit: 'a file inside a .mosc is edited and saved, and the archive holds the change',
  brokenPackage: 'a broken .mosc is reported and never overwritten',
  diagnostic: 'a diagnostic shows on a bad key',
  windowSwitch: 'switching windows and editors logs no failed request',
  completion: 'completion offers the overridable keys',
  definition: 'F12 on scenarioFileName opens the referenced file',
  preview: 'the preview shows the flattened scenario and changes after an edit',
  insidePackage: 'language features work on a file inside a .mosc',
  expression: 'a ${...} shows its value as an inlay hint and in the hover, with the declarations it reads',
  scenarioPath: 'the modular2simple.scenarioPath setting reaches the server',
  roadPath: 'a road appearing in a modular2simple.esmini.roadPath folder outside the workspace clears the road-file warning',
  catalogDirectory: "a catalog appearing in a scenario's catalog Directory outside the workspace clears the catalog error",
  pack: "Pack from the command palette writes a package equivalent to the CLI's",
  flatten: "Flatten from the command palette writes a file equivalent to the CLI's",
  structure: 'Show Structure lists the main file, packages, scenarios and groups',
  renameInPackage: 'renaming a group inside a .mosc updates the package and the files that use it',
  packUnsaved: 'Pack saves unsaved scenario files first, so the package holds what the editor shows, and says so',
  flattenAnyway: 'a refused Flatten offers to write anyway, naming the overrides it skips, as --force does',
  structureFollows: 'the structure follows a cross-file rename and file changes without a Refresh',
  birdsEye: "Show Bird's-Eye View draws the roads and the entities at their start, opens an entity's place, and follows edits",
  birdsEyeRun: "after a run, the bird's-eye view plays the trajectories and shows when the events started",
  birdsEyePackage: "the bird's-eye view shows a scenario inside a .mosc",
  birdsEyeAnalysis:
    "after a run of esmini's highway_merge, the bird's-eye view frames the cars now, follows one with its speed, gap and TTC plots, compares a second run and exports at 1600x900 with legend, time, scale, plots and events",
  runEsmini:
    "Run in esmini from the CodeLens puts esmini's error on the simple scenario's line; a clean run clears it and shows its trajectories",
  runEsminiClean:
    "Run in esmini on a clean modular scenario on e6mini shows no error, and the bird's-eye view draws the road the run loaded, the run named by what ran and ending at its limit",
  runEsminiCutIn: "Run in esmini on esmini's cut-in.xosc runs it: no refusal, no error toast, its lenient forms shown as warnings",
  runEsminiAnyway: 'Run Anyway on a scenario with an error runs it in esmini and says it ran despite the error',
  schemaCompletion: 'schema completion offers the child elements the OpenSCENARIO schema allows',
  schemaDeprecated: 'a deprecated OpenSCENARIO element is struck through',
  ruleCodes:
    "a diagnostic's code is its rule: the ASAM Quality Checker uid linked to its description, shown in the Problems panel, or the project's code; a quick fix still applies",
  newScenario: 'New Modular Scenario… on a folder writes a main with an ego on the chosen road, opens it clean, and never overwrites',
  distributionLens:
    "a distribution file shows its number of concrete scenarios (as vary --count) and Run Variations in a CodeLens; its Run in esmini draws concrete scenario 0 on the ScenarioFile's road",
  variations:
    "the Variations view shows a batch as a sortable, filterable table and scatter, and opens a run in the bird's-eye view, named by its index",
  variationsReasons:
    "Run Variations from the palette shows each run's status and why: esmini's refusal with its message, a StopTrigger at 40 s run to its end, the duration setting's limit named; no progress left beside the result",
  carlaExport:
    "Export for CARLA… from the palette writes the 1.0 file and puts its losses as diagnostics on the simple scenario's lines; a refused export writes nothing",
  carlaCheck:
    "Check in CARLA ScenarioRunner from the palette, with ScenarioRunner 0.9.16 set up, puts ScenarioRunner's error on the source line of the simple scenario",
  carlaSettingsAtOnce:
    "Check in CARLA ScenarioRunner sees a ScenarioRunner folder and a Python written into the user's settings.json in the editor at once, and a second change too, without reloading the window",
  carlaRun:
    "Run in CARLA starts scenario_runner.py on the 1.0 export with the host and port set, in ScenarioRunner's folder; a missing host, no server, an error exit or a Python that does not start is said and never called done",
  extractToSimple:
    'Extract to a simple scenario from the light bulb, with the pick list of attributes, replaces a group by a reference that flattens as before',
  libraryCompose:
    'a main composed from the Scenario Library view with no main open (Insert on a cut-in offers a new composition bench first, then a lead brake and a pedestrian), left modified as an edit (Ctrl+Z undoes the last), saved by the user: 5 steps, checks clean',
  libraryComposeFromNew:
    "from an empty folder, New Modular Scenario… on the library's road, then a cut-in, a lead brake and a pedestrian inserted from the Scenario Library view, each adding its actor as its example main has it, left modified until the user saves: clean, in 7 steps",
  libraryInsertHere:
    'Insert library module here… from the light bulb on a ManeuverGroup picks a module in the quick pick and writes it after that group, clean',
  libraryDrop:
    'dragging a module from the Scenario Library view onto a ManeuverGroup of an open main writes it after that group, as Insert library module here… does, clean',
  libraryDropAsks:
    'dropping a module whose role no entity of the main is named after asks who plays it in a quick pick: cancelled, the main is unchanged; answered, the chosen entity plays it, clean',
  debugScenario:
    'F5 on a scenario stops on the breakpoint on its Event line with the entities in the Variables view; esmini crashing ends the session with a message and the editor lives',
  debugImportLine:
    "F5 on a main with a breakpoint on a ManeuverGroup that imports a group stops when the copy starts, the editor on the breakpoint's line of the main, the copy in the simple scenario in the call stack",
  debugBirdsEyeTurns:
    "F5 on a scenario while the bird's-eye view shows another turns the view to the debugged scenario: its road and its entities at the stop, an event that started and ended before it listed as started",
  debugTimeline:
    'the storyboard timeline opened on a run --trace file draws a row per element at the times esmini logs, and a click on a row opens its source line',
  debugTimelineSession:
    "the storyboard timeline of a debug session, opened while it is stopped, restarted and again after it finished, draws its bars at esmini's times to the stop, the restarted run alone, then to the run's end",
} as const;

export type InsideTestKey = keyof typeof INSIDE_TESTS;

/** Environment variables through which the harness tells the tests inside VS Code where things are. */
export const HARNESS_ENV = {
  endpoint: 'M2S_E2E_ENDPOINT',
  workspace: 'M2S_E2E_WORKSPACE',
  cli: 'M2S_E2E_CLI',
  /** Runs only the tests inside VS Code whose title matches (for debugging one test). */
  grep: 'M2S_E2E_GREP',
} as const;
