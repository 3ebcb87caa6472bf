"""engine.eigensolve.single_thread_blas: every BLAS/OpenMP pool at one thread inside, restored
after, nested use included (the limiter is entered at every solve)."""
from threadpoolctl import threadpool_info

from propwhirl.engine.eigensolve import single_thread_blas


def threads():
    return {(i["internal_api"], i["filepath"]): i["num_threads"] for i in threadpool_info()}


def test_one_thread_inside_and_restored_after():
    before = threads()
    assert before, "no BLAS thread pool found"
    with single_thread_blas():
        assert set(threads().values()) == {1}
        with single_thread_blas():
            assert set(threads().values()) == {1}
        assert set(threads().values()) == {1}
    assert threads() == before
