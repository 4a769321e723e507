"""The CARLA harness (../shared/carla/check.py), run unchanged, with one addition of the tests': each OK
file's result also lists the story elements of the behaviour tree ScenarioRunner built ("tree": the Acts,
ManeuverGroups, Maneuvers, Events and Actions by their OpenSCENARIO names, and the names of the condition
atomics), so a test can tell what of the exported storyboard reached the tree; how its conditions on
parameters fare when ticked ("parameter_ticks", below); and what the stories do when ticked as a run ticks
them ("story_ticks", below, with M2S_CARLA_STORY_TICKS set).

    python3 carlaTree.py CHECK_PY [check.py's own options and files]

check.py forks a server (`--serve`) from its own file; here the server is this script again, so the
addition holds there. Nothing in ../shared is changed.
"""

import importlib.util
import os
import sys


def load_check(path):
    spec = importlib.util.spec_from_file_location('carla_check', path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def story_elements(scenario):
    """What of the storyboard the built tree holds: (kind, name) pairs.

    StoryElementStatusToBlackboard wraps each Act, ManeuverGroup ("SCENE"), Maneuver, Event and Action
    (scenario_runner srunner/scenarios/open_scenario.py _create_behavior); a condition is an atomic named
    after it (srunner/tools/openscenario_parser.py convert_condition_to_atomic, name=condition_name), or,
    for the Storyboard's criteria_, a criterion of that name (_create_test_criteria)."""
    found = set()
    for node in scenario.scenario_tree.iterate():
        kind = getattr(node, 'story_element_type', None)
        element = getattr(node, 'element_name', None)
        if kind is not None and element is not None:
            found.add((str(kind).upper(), str(element)))
        found.add(('NODE', str(node.name)))
        # A criteria_X condition is built as an instance of class X under its own default name.
        found.add(('CLASS', type(node).__name__))
    return sorted([kind, name] for kind, name in found)


def waypoint_atomics(scenario):
    """Each ChangeActorWaypoints of the built tree (srunner/scenariomanager/scenarioatomics/atomic_behaviors.py), as
    [its parent's name, its name, how many waypoints, how many times (None: built without), the last time]."""
    found = []
    for node in scenario.scenario_tree.iterate():
        if type(node).__name__ != 'ChangeActorWaypoints':
            continue
        times = getattr(node, '_times', None)
        parent = node.parent.name if node.parent is not None else None
        found.append([parent, node.name, len(node._waypoints), None if times is None else len(times),
                      None if not times else float(times[-1])])
    return found


def lateral_offsets(scenario):
    """Each ChangeLateralDistance of the built tree (srunner/scenariomanager/scenarioatomics/atomic_behaviors.py), as
    [its name, the offset it will keep from the reference: positive to the right, negative to the left]."""
    return [[node.name, float(node._offset)] for node in scenario.scenario_tree.iterate()
            if type(node).__name__ == 'ChangeLateralDistance']


def parameter_ticks(scenario):
    """ScenarioRunner's own parameter atomics of the built tree, ticked as its first tick would and then once
    more: the Init's ChangeParameters (named InitParams_N, srunner/scenarios/open_scenario.py
    _initialize_parameters), every CheckParameter (each condition on a parameter), every other ChangeParameter
    (the stories' ParameterActions, in tree order), every CheckParameter again. Each CheckParameter's outcome,
    'RUNNING', 'SUCCESS' or 'raises <error>', before and after: what the simulator's ticks would meet."""
    nodes = list(scenario.scenario_tree.iterate())
    changes = [node for node in nodes if type(node).__name__ == 'ChangeParameter']
    checks = [node for node in nodes if type(node).__name__ == 'CheckParameter']

    def tick(node):
        try:
            return str(node.update()).split('.')[-1]
        except Exception as error:  # what ScenarioRunner would raise at that tick
            return 'raises %s: %s' % (type(error).__name__, error)

    for node in changes:
        if node.name.startswith('InitParams'):
            tick(node)
    before = [tick(node) for node in checks]
    for node in changes:
        if not node.name.startswith('InitParams'):
            tick(node)
    after = [tick(node) for node in checks]
    return [[node.name, first, then] for node, first, then in zip(checks, before, after)]


STORY_FRAMES = 10


def story_ticks(scenario):
    """The Init's parameters and the stories ticked as ScenarioManager ticks the tree, STORY_FRAMES frames of
    0.05 s (GameTime advanced as on_carla_tick does: srunner/scenariomanager/timer.py): the first exception a
    tick raises, as 'frame N raises <error>', or None. Only ParametersInit and OSCStories are ticked (the
    actors' Init behaviours need a simulator), so only conditions that need no world (parameters, simulation
    time, storyboard states) ever hold; the others stay RUNNING."""
    from srunner.scenariomanager.timer import GameTime

    class Timestamp:  # carla.Timestamp, as the world's on_tick hands it to GameTime
        def __init__(self, frame):
            self.frame = frame
            self.delta_seconds = 0.05
            self.elapsed_seconds = frame * 0.05

    nodes = {node.name: node for node in scenario.scenario_tree.iterate()}
    parts = [nodes[name] for name in ('ParametersInit', 'OSCStories') if name in nodes]
    for frame in range(1, STORY_FRAMES + 1):
        GameTime.on_carla_tick(Timestamp(frame))
        for part in parts:
            try:
                for _ in part.tick():
                    pass
            except Exception as error:  # what ScenarioRunner would raise at that tick
                return 'frame %d raises %s: %s' % (frame, type(error).__name__, error)
    return None


def spawns(scenario):
    """Where ScenarioRunner spawns each actor: its configuration's transform (openscenario_configuration.py
    _get_actor_transform), as {rolename: [x, y, z, yaw in degrees]}."""
    config = scenario.config
    placed = {}
    for actor in list(config.ego_vehicles) + list(config.other_actors):
        location, rotation = actor.transform.location, actor.transform.rotation
        placed[actor.rolename] = [round(location.x, 4), round(location.y, 4), round(location.z, 4), round(rotation.yaw, 4)]
    return placed


def main():
    check_path = os.environ.get('M2S_CARLA_CHECK')
    argv = sys.argv[1:]
    if check_path is None:
        if not argv:
            print('usage: carlaTree.py CHECK_PY [check.py options] FILES', file=sys.stderr)
            return 2
        check_path, argv = os.path.abspath(argv[0]), argv[1:]
        os.environ['M2S_CARLA_CHECK'] = check_path  # for the server, which check.py starts from this file
    check = load_check(check_path)
    check.__file__ = os.path.abspath(__file__)  # Server starts `python3 <__file__> --serve`: this script
    original_run_file = check.run_file

    def run_file(env, path, opts, emit):
        built = {}
        original_lazy_refs = check._lazy_refs

        def lazy_refs(scenario, parameter_ref):
            # Called once the tree is built (run_file, stage build): the moment to read it.
            built['tree'] = story_elements(scenario)
            from srunner.scenariomanager.carla_data_provider import CarlaDataProvider
            declared = dict(CarlaDataProvider._global_osc_parameters)
            built['parameter_ticks'] = parameter_ticks(scenario)
            # parameter_ticks ran the ParameterActions: the run starts from the parameters as declared.
            CarlaDataProvider._global_osc_parameters.clear()
            CarlaDataProvider._global_osc_parameters.update(declared)
            # Opt-in: a run ticks every action, a CustomCommandAction's shell command included.
            if os.environ.get('M2S_CARLA_STORY_TICKS'):
                built['story_ticks'] = story_ticks(scenario)
            built['spawns'] = spawns(scenario)
            built['waypoints'] = waypoint_atomics(scenario)
            built['lateral_offsets'] = lateral_offsets(scenario)
            return original_lazy_refs(scenario, parameter_ref)

        check._lazy_refs = lazy_refs

        def emit_with_tree(kind, payload):
            if kind == 'RESULT' and 'tree' in built:
                payload['tree'] = built['tree']
                payload['parameter_ticks'] = built['parameter_ticks']
                payload['spawns'] = built['spawns']
                payload['waypoints'] = built['waypoints']
                payload['lateral_offsets'] = built['lateral_offsets']
                if 'story_ticks' in built:
                    payload['story_ticks'] = built['story_ticks']
            emit(kind, payload)

        return original_run_file(env, path, opts, emit_with_tree)

    check.run_file = run_file
    return check.main(argv)


if __name__ == '__main__':
    sys.exit(main())
