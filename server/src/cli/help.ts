import { FORMAT_HELP } from './format';
import { MODULARIZE_HELP } from './modularize';
import { RUN_HELP } from './run';
import { VARY_HELP } from './vary';
import { BATCH_HELP } from './batch';
import { WORKER_HELP } from './worker';
import { VERSION } from './common';
import { EXPORT_HELP } from './export';
import { READING_OPTIONS_HELP, SIMULATOR_OPTION_HELP } from './options';

export const HELP = `modular2simple ${VERSION}: pack, flatten and check modular OpenSCENARIO scenarios

Usage:
  modular2simple flatten INPUT [-o FILE]           flatten a .mosc, a main.xosc or an unpacked folder
  modular2simple flatten INPUT... --out-dir DIR    flatten several inputs into DIR/NAME.xosc
  modular2simple pack FOLDER -o FILE.mosc          pack an unpacked folder and all it references
  modular2simple pack FILE... -o FILE.mosc         pack files at the root of a package (one main.xosc)
  modular2simple check PATH... [--format json|sarif]
                                                   report every problem, as a compiler does
  modular2simple qc-bundle -c CONFIG.xml [--out-dir DIR]
                                                   check as a checker bundle of ASAM's Quality Checker
                                                   Framework (its .xqar into DIR); --manifest prints
                                                   the module manifest that registers it
  modular2simple stats LIBRARY [--format json]     lines of code of a library (the paper's Table 1)
  modular2simple run INPUT... [--check]            flatten and run in esmini; its messages on the source lines
  modular2simple vary FILE [--count|--index I|--out-dir DIR]
                                                   concrete scenarios of a parameter distribution
  modular2simple modularize INPUT... --out-dir DIR [--dry-run]
                                                   extract the groups that recur into simple scenarios
  modular2simple batch FILE --results DIR [--jobs N] [--queue redis://HOST:PORT]
                                                   run them all in esmini; results.csv and results.json
  modular2simple worker --queue redis://HOST:PORT    run a batch's runs from a Redis queue
  modular2simple export INPUT --target carla -o OUT.xosc [--report LOSSES.json] [--carla 0.9.15|0.9.16]
                                                   OpenSCENARIO 1.0 that CARLA's ScenarioRunner builds,
                                                   with a report of what it cannot keep
  modular2simple library list|show NAME|path [--format json]
                                                   the scenario library: modules a main names as
                                                   scenarioFileName="library:NAME"
  modular2simple library templates|new TEMPLATE -o FILE.xosc
                                                   test scenarios composed from library modules
${FORMAT_HELP}

Compatible with the original tool:
  modular2simple -cxm|--convert-xosc-into-mosc IN... OUT.mosc
  modular2simple -cmx|--convert-mosc-to-xosc IN.mosc OUT.xosc

Each command prints its own options and exit codes: modular2simple COMMAND --help (or -h).

Options:
  -o, --output FILE         the file to write (flatten: '-' or no -o prints to standard output)
  --out-dir DIR             the folder to write into: flatten and vary (a file per input or scenario),
                            modularize and qc-bundle (which also take -o DIR, their older form)
  --force                   flatten, run: write (or run) whatever can be produced despite errors,
                            listing them; overrides that cannot apply (unknown keys, attributes
                            without default) are skipped, as the original did
  --include-scenario-path   pack: also store files found through SCENARIO_PATH
  --self-contained          pack: store the road networks, catalogs and other files the scenarios
                            name inside the package (else pack warns about each one left outside)
  --format text|json|sarif  output format of check (sarif: SARIF 2.1.0 for CI dashboards) and
                            stats (text or json)
${SIMULATOR_OPTION_HELP} (check, flatten)
  --check                   format: list the files that would change and write nothing (exit 1 if any)
  --width N                 format: past N columns a start tag puts each attribute on its own line (120)
  --indent N|tab            format: the indentation (default: what the file uses, else 2 spaces)
  The options below are flatten's, pack's, check's and stats'; run takes --scenario-path, --road-path,
  the four --max-* bounds and -q too (each command's --help lists the options it takes):
${READING_OPTIONS_HELP}
  -h, --help                this help
  -v, --version             the version

${RUN_HELP}

${VARY_HELP}

${MODULARIZE_HELP}

${BATCH_HELP}

${WORKER_HELP}

${EXPORT_HELP}

Environment:
  SCENARIO_PATH             folders searched for referenced scenarios (separated by ';' or ':')

Exit codes:
  0 success (warnings may have been printed)
  1 the input has errors; nothing was written (with --force: only what cannot be produced at all)
  2 wrong usage
  3 the output could not be written; nothing was changed
  4 internal error (a bug: please report it with the input)`;
