#!/usr/bin/env python3
"""Does CARLA's ScenarioRunner load this OpenSCENARIO file and build its behaviour tree? (Modular2Simple)

    python scenario_runner_check.py --scenario-runner DIR [--towns Town01,Town02,...] FILE.xosc

Run with a Python that has ScenarioRunner's requirements (its requirements.txt: py_trees, xmlschema,
numpy, networkx, shapely, ...). No CARLA server is needed: the `carla` module is ScenarioRunner's own
stand-in for unit tests (DIR/srunner/tests/carla_mocks), completed below with what loading and building
a scenario asks of a server. The file is loaded as `scenario_runner.py --openscenario FILE` loads it
(OpenScenarioConfiguration: schema, version, parameters, catalogs, town, actors), the egos are spawned
as its _prepare_ego_vehicles does, and OpenScenario(...) builds the behaviour tree. Nothing is ticked:
what fails only while a scenario runs in CARLA is not seen.

Prints one JSON object on stdout:
    {"status": "built" | "refused" | "not-scenario-runner" | "requirements" | "error",
     "stage": "schema" | "version" | "configuration" | "build" | null,
     "reason": "TypeError: ...", "where": "srunner/...py:123 function", "source_line": "...",
     "element": {"index": N, "tag": "...", "name": "..."} | null,   (N: the element's place in document order)
     "warnings": [...], "tree_nodes": N, "town": "...", "egos": [...], "others": [...]}
Exit status: 0 built, 1 refused, 3 not ScenarioRunner or its requirements missing, 4 this script failed.
"""

import argparse
import io
import json
import logging
import os
import sys
import traceback
import types

RESULT_OUT = sys.stdout


def emit(result, code):
    RESULT_OUT.write(json.dumps(result) + '\n')
    RESULT_OUT.flush()
    sys.exit(code)


def short(error):
    lines = str(error).strip().splitlines()
    return ('%s: %s' % (type(error).__name__, lines[0] if lines else ''))[:500]


# ------------------------------------------------------------------------------- the CARLA stand-in

def complete_mock(carla, towns):
    """What ScenarioRunner's loader asks of a CARLA server that its unit-test mock lacks (each at most once)."""

    class Blueprint(carla.CarlaBluePrint):
        # The id becomes the spawned actor's type_id, which atomics split and criteria search while being built.
        def __init__(self, blueprint_id='vehicle.stub.stub'):
            super().__init__()
            self.id = blueprint_id

    class BlueprintLibrary(carla.CarlaBluePrintLibrary):
        # As in CARLA, a name that is no blueprint pattern (no '.' or '*') matches nothing: ScenarioRunner then
        # takes its category's default; any dotted pattern is taken to exist (there is no list to check it against).
        def filter(self, pattern):
            if '.' not in pattern and '*' not in pattern:
                return []
            return [Blueprint(pattern.replace('*', 'stub'))]

        def find(self, blueprint_id):
            return Blueprint(blueprint_id)

    carla.CarlaBluePrint, carla.CarlaBluePrintLibrary = Blueprint, BlueprintLibrary
    carla.World.get_blueprint_library = lambda self: BlueprintLibrary()

    original_weather = carla.WeatherParameters

    class WeatherParameters(original_weather):
        # ScenarioConfiguration passes keyword arguments, as CARLA's class takes them.
        def __init__(self, **values):
            self.__dict__.update(values)

    carla.WeatherParameters = WeatherParameters

    if not hasattr(carla, 'BoundingBox'):
        class BoundingBox:
            def __init__(self, location=None, extent=None):
                self.location = location or carla.Location()
                self.extent = extent or carla.Vector3D(1.0, 1.0, 1.0)
        carla.BoundingBox = BoundingBox
    if not hasattr(carla.Actor, 'bounding_box'):
        carla.Actor.bounding_box = carla.BoundingBox()
    for step in ('next', 'previous'):
        if not hasattr(carla.Waypoint, step):
            setattr(carla.Waypoint, step, lambda self, distance: [carla.Waypoint()])
    if not hasattr(carla.Map, 'to_opendrive'):
        carla.Map.to_opendrive = lambda self: ''

    def spawned(blueprint):
        blueprint_id = str(getattr(blueprint, 'id', ''))
        kind = carla.Walker if blueprint_id.startswith('walker.') else \
            carla.Vehicle if blueprint_id.startswith('vehicle.') else carla.Actor
        actor = kind()
        actor.type_id = blueprint_id
        return actor

    def add_actor(world, blueprint):
        actor = spawned(blueprint)
        actor.attributes['role_name'] = blueprint.attributes.get('role_name', '')
        actor.id = len(world.actors)
        world.actors.append(actor)
        return actor

    carla.World.try_spawn_actor = lambda self, blueprint, transform, *rest, **named: add_actor(self, blueprint)
    carla.World.spawn_actor = lambda self, blueprint, transform, *rest, **named: add_actor(self, blueprint)

    def get_actors(self, ids=None):
        # CARLA answers every actor when no ids are given (a position relative to an actor spawned before needs it).
        return carla.ActorList([actor for actor in self.actors if ids is None or actor.id in ids])

    carla.World.get_actors = get_actors

    class Response:
        def __init__(self, actor_id):
            self.actor_id = actor_id
            self.error = None

    def apply_batch_sync(self, batch, sync_mode=False):
        return [Response(add_actor(self.world, command.blueprint).id) for command in batch if command is not None]

    carla.Client.apply_batch_sync = apply_batch_sync

    def load_world(self, name, *rest, **named):
        # ScenarioRunner loops until the map's name is the town; like CARLA, a name that is no map fails.
        town = name.split('/')[-1]
        if towns is not None and town not in towns:
            raise RuntimeError('map not found: %s is not one of the CARLA maps (%s)' % (town, ', '.join(sorted(towns))))
        carla.Map.name = 'Carla/Maps/' + town
        return self.world

    def generate_opendrive_world(self, opendrive, parameters=None, reset_settings=True):
        carla.Map.name = 'OpenDriveMap'
        return self.world

    carla.Client.load_world = load_world
    carla.Client.generate_opendrive_world = generate_opendrive_world
    if not hasattr(carla, 'OpendriveGenerationParameters'):
        class OpendriveGenerationParameters:
            def __init__(self, *values, **named):
                self.__dict__.update(named)
        carla.OpendriveGenerationParameters = OpendriveGenerationParameters


def stand_in_modules():
    """Modules a CARLA installation brings that the mock's copy of CARLA's agents/ predates, or that only draw."""
    try:
        import agents.navigation.constant_velocity_agent  # noqa: F401
    except ImportError:
        from agents.navigation.basic_agent import BasicAgent
        module = types.ModuleType('agents.navigation.constant_velocity_agent')

        class ConstantVelocityAgent(BasicAgent):
            pass
        module.ConstantVelocityAgent = ConstantVelocityAgent
        sys.modules[module.__name__] = module
    try:
        import cv2  # noqa: F401
    except ImportError:
        # Only the camera window of a run uses OpenCV; importing a controller module must not fail for it.
        module = types.ModuleType('cv2')

        def missing(name):
            raise AttributeError('cv2.%s: OpenCV is not installed (only stood in for while checking)' % name)
        module.__getattr__ = missing
        sys.modules['cv2'] = module


# ------------------------------------------------------------------------------- where it failed

class Places:
    """The elements of the file in document order, to name where ScenarioRunner failed."""

    def __init__(self, root):
        self.root = root
        self.index = {}
        self.depth = {}
        stack = [(root, 0)]
        order = 0
        while stack:
            element, depth = stack.pop()
            self.index[id(element)] = order
            self.depth[id(element)] = depth
            order += 1
            stack.extend((child, depth + 1) for child in reversed(list(element)))

    def describe(self, element):
        place = self.index.get(id(element))
        if place is None:  # a copy ScenarioRunner made (catalog entries): the first element written the same way
            for candidate in self.root.iter(element.tag):
                if candidate.attrib == element.attrib:
                    place = self.index[id(candidate)]
                    break
        return {'index': place, 'tag': element.tag, 'name': element.attrib.get('name')}

    def deepest(self, elements):
        known = [element for element in elements if id(element) in self.index]
        pool = known or elements
        return max(pool, key=lambda element: self.depth.get(id(element), -1)) if pool else None


def frames_of(error):
    frames = []
    tb = error.__traceback__
    while tb is not None:
        frames.append(tb.tb_frame)
        tb = tb.tb_next
    return frames


def failing_element(error, places, element_type):
    """The most specific element the innermost frame that held one was working on."""
    found = getattr(error, 'elem', None)
    if isinstance(found, element_type):
        return places.describe(found)
    for frame in reversed(frames_of(error)):
        elements = [value for value in frame.f_locals.values() if isinstance(value, element_type)]
        if elements:
            return places.describe(places.deepest(elements))
    return None


def scenario_runner_frame(error, roots):
    """'srunner/tools/openscenario_parser.py:123 function' and its code: the innermost frame in ScenarioRunner."""
    pick = None
    for frame in traceback.extract_tb(error.__traceback__):
        if any(frame.filename.startswith(root + os.sep) for root in roots):
            pick = frame
    if pick is None:
        return None, None
    name = pick.filename
    for root in roots:
        if name.startswith(root + os.sep):
            name = os.path.relpath(name, root)
            break
    return '%s:%d %s' % (name, pick.lineno, pick.name), (pick.line or '').strip()


# ------------------------------------------------------------------------------- the check

def check(scenario_runner, scenario, towns):
    scenario_runner = os.path.abspath(scenario_runner)
    for needed in ('scenario_runner.py', os.path.join('srunner', 'scenarioconfigs', 'openscenario_configuration.py')):
        if not os.path.isfile(os.path.join(scenario_runner, needed)):
            emit({'status': 'not-scenario-runner',
                  'reason': '%s is not a ScenarioRunner folder: it has no %s' % (scenario_runner, needed)}, 3)
    mock = os.path.join(scenario_runner, 'srunner', 'tests', 'carla_mocks')
    if not os.path.isfile(os.path.join(mock, 'carla.py')):
        emit({'status': 'not-scenario-runner',
              'reason': '%s has no srunner/tests/carla_mocks/carla.py, the stand-in for CARLA that this check '
                        'builds on (in ScenarioRunner since 2021; 0.9.16 has it)' % scenario_runner}, 3)
    # The stand-in first: a CARLA Python API installed in this Python must not be the one imported.
    sys.path[:0] = [mock, scenario_runner]
    for name in [name for name in sys.modules if name == 'carla' or name.startswith('agents')]:
        del sys.modules[name]

    captured = io.StringIO()
    sys.stdout = captured
    logging.basicConfig(stream=captured, level=logging.WARNING, format='%(name)s %(levelname)s %(message)s')
    try:
        import xml.etree.ElementTree as ET
        import carla
        complete_mock(carla, towns)
        stand_in_modules()
        from srunner.scenarioconfigs.openscenario_configuration import OpenScenarioConfiguration
        from srunner.scenariomanager.carla_data_provider import CarlaDataProvider
        from srunner.scenarios.open_scenario import OpenScenario
    except ImportError as error:
        emit({'status': 'requirements', 'reason': short(error), 'module': getattr(error, 'name', None),
              'python': sys.executable, 'output': captured.getvalue()[-2000:]}, 3)

    result = {'status': 'refused', 'stage': None, 'reason': None, 'element': None, 'where': None,
              'source_line': None}

    def warnings():
        return [line.strip() for line in captured.getvalue().splitlines() if line.strip()][:100]

    try:
        places = Places(ET.parse(scenario).getroot())
    except (ET.ParseError, OSError) as error:
        result.update(stage='schema', reason=short(error))
        emit(result, 1)
    roots = [scenario_runner, mock]

    client = carla.Client()
    try:
        config = OpenScenarioConfiguration(scenario, client, {})
    except BaseException as error:  # ScenarioRunner refuses: whatever it raised is its message
        functions = [frame.f_code.co_name for frame in frames_of(error)]
        stage = 'schema' if any('_validate_openscenario' in name for name in functions) else \
            'version' if '_check_version' in functions else 'configuration'
        where, line = scenario_runner_frame(error, roots)
        result.update(stage=stage, reason=short(error), where=where, source_line=line,
                      element=failing_element(error, places, ET.Element), warnings=warnings())
        emit(result, 1)
    town = config.town
    result.update(town=os.path.basename(town) if town and '.xodr' in town else town,
                  egos=[actor.rolename for actor in config.ego_vehicles],
                  others=[actor.rolename for actor in config.other_actors])
    places = Places(config.xml_tree.getroot())
    try:
        CarlaDataProvider.set_client(client)
        egos = [CarlaDataProvider.request_new_actor(vehicle.model, vehicle.transform, vehicle.rolename,
                                                    random_location=vehicle.random_location, color=vehicle.color,
                                                    actor_category=vehicle.category)
                for vehicle in config.ego_vehicles]
        built = OpenScenario(world=client.get_world(), ego_vehicles=egos, config=config, config_file=scenario,
                             timeout=100000)
    except BaseException as error:
        where, line = scenario_runner_frame(error, roots)
        result.update(stage='build', reason=short(error), where=where, source_line=line,
                      element=failing_element(error, places, ET.Element), warnings=warnings())
        emit(result, 1)
    result.update(status='built', tree_nodes=sum(1 for _ in built.scenario_tree.iterate()), warnings=warnings())
    emit(result, 0)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--scenario-runner', required=True, help='the folder of ScenarioRunner (scenario_runner.py)')
    parser.add_argument('--towns', help='the CARLA maps a town name may be, comma-separated (default: any)')
    parser.add_argument('scenario')
    options = parser.parse_args(argv)
    towns = set(options.towns.split(',')) if options.towns else None
    try:
        check(options.scenario_runner, os.path.abspath(options.scenario), towns)
    except SystemExit:
        raise
    except BaseException as error:  # this script's own failure, with its stack
        emit({'status': 'error', 'reason': short(error), 'traceback': traceback.format_exc()[-4000:]}, 4)


if __name__ == '__main__':
    main(sys.argv[1:])
