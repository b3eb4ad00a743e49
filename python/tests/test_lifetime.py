"""No reference cycle keeps a Simulation alive: 100 created and dropped are all freed."""
import gc
import weakref

import jellysim


def test_hundred_simulations_are_freed(cheap_scene):
    gc.collect()
    before = jellysim._live_simulations()
    refs = []
    for _ in range(100):
        s = jellysim.Simulation(cheap_scene)
        s.step()
        s.velocity_field()
        s.metrics()
        refs.append(weakref.ref(s))
        del s
    # Reference counting alone frees them: no cycle for the collector to find.
    assert jellysim._live_simulations() == before
    assert all(r() is None for r in refs)
    gc.collect()
    assert jellysim._live_simulations() == before
