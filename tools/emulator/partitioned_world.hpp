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

#pragma once

#include <cstdint>
#include <vector>

#include <enki/PhysicalEngine.h>

namespace aseba::arena
{

class PartitionedWorld : public Enki::World
{
  public:
    // A square arena of `width` x `height` cm with walls of `wall_color`.
    PartitionedWorld(double width, double height, const Enki::Color &wall_color);

    // Enki's World::step, with the pair loops over nearby pairs only.
    void step(double dt, unsigned physics_oversampling = 1) override;

    // Collision passes in which an object moved more than the margin allows,
    // so that the run may differ from Enki's all-pairs step (0 expected).
    uint64_t margin_overruns() const
    {
        return margin_overruns_;
    }

  private:
    // The objects in Enki's order, each with how far its sensors reach (0:
    // none; negative: unknown, so it meets every object).
    void take_objects();
    // Buckets the objects' bounding circles into square cells.
    void build_grid();
    // The objects (indices, ascending) whose bounding circles come within
    // `reach` of the circle of object `index`.
    void objects_near(size_t index, double reach, std::vector<uint32_t> &found);
    void collide_nearby_pairs();
    void sense_nearby_objects(double dt);

    std::vector<Enki::PhysicalObject *> objects_;
    std::vector<double> sensing_ranges_;
    double largest_radius_ = 0;
    double cell_size_ = 1;
    long columns_ = 1, rows_ = 1;
    // Object indices per cell: cell c holds cell_objects_[cell_starts_[c]
    // .. cell_starts_[c + 1]).
    std::vector<uint32_t> cell_starts_;
    std::vector<uint32_t> cell_objects_;
    std::vector<uint32_t> cell_fill_; // where the next object of each cell goes
    std::vector<uint32_t> found_;
    std::vector<uint32_t> last_seen_;
    uint32_t visit_ = 0;
    uint64_t margin_overruns_ = 0;
};

} // namespace aseba::arena
