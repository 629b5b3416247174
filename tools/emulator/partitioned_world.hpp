// Enki's world stepped with a grid: the same step as Enki's World::step,
// call for call and in the same order, but each object meets only the
// objects near enough to collide with it or to be sensed by it, instead of
// every other object (Enki compares every pair: O(N²) at 1,000 robots, most
// of a step). The runs stay bit-identical to Enki's own step.
//
// Why the result is the same: Enki's pair loops call collideObjects(a, b)
// for a before b in its object order, and doLocalInteractions(a, b) for
// every a != b; each call does nothing unless the two are within reach
// (their radii, plus the sensor's range). The grid finds every pair within
// reach, plus a margin, and the calls are made in Enki's order. Collisions
// move objects during the pass, so a far pair could come within reach
// before its turn: the step checks that no object moved more than half the
// margin during the pass, which keeps every skipped pair out of reach, and
// counts the passes where that did not hold (never seen: an object moves by
// the depth of its contacts, a fraction of a millimetre a step).
//
// The sensing pass may run on several threads (set_parallel_for): the
// calls that start an object's sensors, doLocalInteractions(a, b) and the
// walls' pass write only a's own sensors (Enki's IR sensors and camera keep
// their rays and pixels in themselves and draw no random number there), so
// each object's calls, made in Enki's order on whichever thread, give the
// same sensors whatever the thread count. What draws noise from shared
// generators (the sensors' finalize, the wheels' controlStep) stays on the
// calling thread, in Enki's order.

#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <enki/PhysicalEngine.h>

namespace aseba::arena
{

class PartitionedWorld : public Enki::World
{
  public:
    // A square arena of `width` x `height` cm with walls of `wall_color`.
    PartitionedWorld(double width, double height, const Enki::Color &wall_color);

    // Calls work(begin, end) on pieces covering 0..count, possibly on
    // several threads at once, and returns when every piece is done.
    using ParallelFor =
      std::function<void(size_t count, const std::function<void(size_t begin, size_t end)> &work)>;

    // Enki's World::step, with the pair loops over nearby pairs only.
    void step(double dt, unsigned physics_oversampling = 1) override;

    // Lets the sensing pass share its objects out through `parallel_for`
    // (by default it runs them in order on the calling thread).
    void set_parallel_for(ParallelFor parallel_for);

    // Collision passes in which an object moved more than the margin allows,
    // so that the run may differ from Enki's all-pairs step (0 expected).
    uint64_t margin_overruns() const
    {
        return margin_overruns_;
    }

  private:
    // What a neighbour query needs besides the grid, one per thread that
    // queries: the objects found.
    struct Query {
        std::vector<uint32_t> found;
    };

    // The objects in Enki's order, each with how far its sensors reach (0:
    // none; negative: unknown, so it meets every object).
    void take_objects();
    // Whether the object is wider than a cell: every query meets it, the
    // grid does not hold it.
    bool outside_grid(size_t index) const;
    // Buckets the objects no wider than a cell by the cell of their centre.
    void build_grid();
    // The cell (0..count - 1) of a coordinate, clamped to the border cells.
    long cell_of(double at, long count) const
    {
        return std::clamp(long(std::floor(at / cell_size_)), 0L, count - 1);
    }
    // The objects (indices, ascending) whose bounding circles come within
    // `reach` of the circle of object `index`, into `query.found`.
    void objects_near(size_t index, double reach, Query &query) const;
    void collide_nearby_pairs();
    void sense_nearby_objects(double dt);
    // The sensing pass of objects begin..end: each object's sensors start
    // and meet the nearby objects, then the walls.
    void sense_objects(double dt, size_t begin, size_t end, Query &query);

    std::vector<Enki::PhysicalObject *> objects_;
    std::vector<double> sensing_ranges_;
    double cell_size_ = 1;
    long columns_ = 1, rows_ = 1;
    // Object indices per cell: cell c holds cell_objects_[cell_starts_[c]
    // .. cell_starts_[c + 1]).
    std::vector<uint32_t> cell_starts_;
    std::vector<uint32_t> cell_objects_;
    std::vector<uint32_t> cell_fill_;     // where the next object of each cell goes
    std::vector<uint32_t> object_cells_;  // each object's cell (UINT32_MAX: none)
    std::vector<uint32_t> large_objects_; // wider than a cell: outside the grid
    double grid_radius_ = 0;              // the largest radius in the grid
    Query query_;                         // the calling thread's
    ParallelFor parallel_for_;
    uint64_t margin_overruns_ = 0;
};

} // namespace aseba::arena
