import { FORMAT_HELP } from './format';
import { MODULARIZE_HELP } from './modularize';
import { RUN_HELP } from './run';
import { VARY_HELP } from './vary';
import { BATCH_HELP, WORKER_HELP } from './batch';
import { VERSION } from './common';
import { EXPORT_HELP } from './export';

export const HELP = `modular2simple ${VERSION}: pack, flatten and check modular OpenSCENARIO scenarios

Usage:
  modular2simple flatten INPUT [-o OUT.xosc]       flatten a .mosc, a main.xosc or an unpacked folder
  modular2simple flatten INPUT... --out-dir DIR    flatten several inputs into DIR/NAME.xosc
  modular2simple pack FOLDER -o OUT.mosc           pack an unpacked folder and all it references
  modular2simple pack FILE... -o OUT.mosc          pack files at the root of a package (one main.xosc)
  modular2simple check PATH... [--format json|sarif]
                                                   report every problem, as a compiler does
  modular2simple qc-bundle -c CONFIG.xml [-o DIR]   check as a checker bundle of ASAM's Quality Checker
                                                   Framework (its .xqar into DIR); --manifest prints
                                                   the module manifest that registers it
  modular2simple stats LIBRARY [--format json]     lines of code of a library (the paper's Table 1)
  modular2simple run INPUT... [--check]            flatten and run in esmini; its messages on the source lines
  modular2simple vary FILE [--count|--index I|--out-dir DIR]
                                                   concrete scenarios of a parameter distribution
  modular2simple modularize INPUT... -o OUT [--dry-run]
                                                   extract the groups that recur into simple scenarios
  modular2simple batch FILE --results DIR [--jobs N] [--queue redis://HOST:PORT]
                                                   run them all in esmini; results.csv and results.json
  modular2simple worker --queue redis://HOST:PORT    run a batch's runs from a Redis queue
  modular2simple export INPUT --target carla -o OUT.xosc [--report LOSSES.json] [--carla 0.9.15|0.9.16]
                                                   OpenSCENARIO 1.0 that CARLA's ScenarioRunner builds,
                                                   with a report of what it cannot keep
${FORMAT_HELP}

Compatible with the original tool:
  modular2simple -cxm|--convert-xosc-into-mosc IN... OUT.mosc
  modular2simple -cmx|--convert-mosc-to-xosc IN.mosc OUT.xosc

Options:
  -o, --output FILE         where to write (flatten: '-' or no -o prints to standard output)
  --out-dir DIR             output folder for several inputs
  --force                   flatten, run: write (or run) whatever can be produced despite errors,
                            listing them; overrides that cannot apply (unknown keys, attributes
                            without default) are skipped, as the original did
  --scenario-path DIRS      folders searched after the package, before SCENARIO_PATH's own
                            (separated by ';' or ':')
  --root DIR                where the search upward from an unpacked folder stops (default: the
                            working directory, or the input's folder when it lies elsewhere)
  --include-scenario-path   pack: also store files found through SCENARIO_PATH
  --self-contained          pack: store the road networks, catalogs and other files the scenarios
                            name inside the package (else pack warns about each one left outside)
  --format text|json|sarif  output format of check (sarif: SARIF 2.1.0 for CI dashboards) and
                            stats (text or json)
  --simulator asam|carla|esmini
                            check, flatten: also warn about what this simulator does not run
                            (default asam: the standard alone)
  --check                   format: list the files that would change and write nothing (exit 1 if any)
  --width N                 format: past N columns a start tag puts each attribute on its own line (120)
  --indent N|tab            format: the indentation (default: what the file uses, else 2 spaces)
  --schema-version V        the OpenSCENARIO schema files are checked against: auto (each file's
                            FileHeader, the default), 1.0, 1.1, 1.2, 1.3, or off
  --max-file-size SIZE      largest scenario file or package entry read (default 32M)
  --max-unpacked-size SIZE  bytes one run may unpack from packages, all together (default 128M)
  --max-output-size SIZE    characters of one flattened result (default 8M)
  --max-depth N             files in one chain of references, nested packages included (default 64)
  -q, --quiet               print errors only
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
