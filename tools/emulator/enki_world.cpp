// The Enki world of the simulated arena and the per-robot host_world tables
// that show it to each robot's drivers (see enki_world.hpp and
// docs/arena-format.md).

#include "enki_world.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <new>
#include <utility>

namespace aseba::arena
{
namespace
{

constexpr double pi = 3.14159265358979323846;
constexpr double radians_per_degree = pi / 180;

// Enki's e-puck (robots/e-puck/EPuck.cpp, measured in
// ../shared/research/enki.md §A.2): body, wheels, sensors.
constexpr double body_radius = 3.7;
constexpr double body_height = 4.7;
constexpr double body_mass = 152;
const Enki::Color body_color(0, 0.7, 0);
constexpr double wheel_distance = 5.1;
// Enki clamps wheel speeds here; the firmware already limits them to 1000
// steps/s, so the clamp only needs to stay clear of step-count rounding.
constexpr double wheel_speed_limit = 2 * 12.8;

constexpr double ir_height = 2.5;
constexpr double ir_range = 12;
constexpr double ir_response_maximum = 3731;
constexpr double ir_response_x0 = 0.3;
constexpr double ir_response_c = 0.7;
constexpr double ir_noise_sd = 10;
struct IrPlacement {
    double x, y, heading_degrees;
};
constexpr IrPlacement ir_placements[EnkiEpuck::ir_count] = {
    { 3.35, -1.05, -18 }, { 2.3, -2.6, -45 }, { 0, -3.3, -90 }, { -3.0, -1.8, -142 },
    { -3.0, 1.8, 142 },   { 0, 3.3, 90 },     { 2.3, 2.6, 45 }, { 3.35, 1.05, 18 },
};

// The camera: Enki's place for it, the real sensor's field of view (hardware
// §3.5: about 56° x 42°), and the range of Enki's camera, which draws what
// rows above the horizon see (objects further away are not drawn: Enki's
// camera costs O(robots²) otherwise).
constexpr double camera_forward = 3.7;
constexpr double camera_height = 2.2;
constexpr double camera_horizontal_field = 56 * radians_per_degree;
constexpr double camera_vertical_field = 42 * radians_per_degree;
constexpr double camera_horizon_range = 40;
// The cells in which the camera looks for the robots near its lens (cm):
// about as wide as the floor rays of the default tilt reach (2 to 14 cm)
// with a robot's radius.
constexpr double camera_cell_size = 10;
constexpr unsigned camera_window_rows = 120;
constexpr unsigned camera_row_pixels = 120;
constexpr unsigned camera_row_bytes = 2 * camera_row_pixels;
// PO3030K identification (hardware §3.5): registers 0x00, 0x01.
constexpr uint8_t camera_id_high = 0x30;
constexpr uint8_t camera_id_low = 0x30;
constexpr unsigned rgb565_red_levels = 31;
constexpr unsigned rgb565_green_levels = 63;
constexpr unsigned rgb565_blue_levels = 31;

// Obstacles are walls for the robots: taller than their body and sensors.
constexpr double obstacle_height = 10;
constexpr double static_mass = -1;

// Motors (hardware §3.6): 1000 steps a wheel turn, 12.8 cm a turn; the
// full-step phase patterns (bit 3 = A .. bit 0 = D) in sequence order.
constexpr double centimetres_per_step = 12.8 / 1000;
constexpr uint8_t phase_patterns[4] = { 0x5, 0x6, 0xA, 0x9 };
constexpr int phase_count = 4;

// The accelerometer (hardware §3.3): counts at 0 g and per g, +X right,
// +Y backward, Z up.
constexpr double zero_g_counts = 2048;
constexpr double counts_per_g = 768;
constexpr double gravity = 981; // cm/s²
constexpr double adc_maximum = 4095;

constexpr uint16_t selector_positions = 16;
constexpr uint8_t selector_bits = 4;
static_assert(selector_positions == 1u << selector_bits);
// The microphones' analog inputs (AN2..AN4), as a scan's channel mask.
constexpr unsigned microphone_count = EPUCK_ADC_ACCELEROMETER_X - EPUCK_ADC_MICROPHONE_0;
constexpr uint16_t microphone_channels = ((1u << microphone_count) - 1u) << EPUCK_ADC_MICROPHONE_0;
// The boards' cycles in one world step (a whole number for 10 ms).
constexpr uint64_t step_cycles =
  uint64_t(EnkiWorld::step_seconds * double(HOST_CYCLES_PER_SECOND) + 0.5);

enum Motor { left_motor, right_motor };

} // namespace

struct EnkiWorld::RobotState {
    host_world table;
    EnkiWorld *world = nullptr;
    size_t index = 0;
    std::array<bool, EPUCK_PIN_COUNT> output{};
    // Per motor: the phase index last driven, and steps since the last
    // Enki step (+ forward).
    int phase[2] = { 0, 0 };
    int32_t steps[2] = { 0, 0 };
    // Per motor: its phase lines as driven (bit 3 = A .. bit 0 = D).
    uint8_t lines[2] = { 0, 0 };
    double wheel_speed[2] = { 0, 0 };
    std::array<uint8_t, 256> camera_registers{};
    // The row last rendered, for the step it was rendered in.
    uint64_t rendered_step = UINT64_MAX;
    uint16_t rendered_row = 0;
    uint8_t row_bytes[camera_row_bytes] = {};
    // The impact the accelerometer feels, and for how many more steps.
    Enki::Vector impact;
    unsigned impact_steps_left = 0;
    // Seconds spent without a break on shock areas since the last knock.
    double shock_clock = 0;
    // The ADC readings of this step, worked out once per step since the
    // firmware samples far more often than the world changes.
    uint16_t proximity_lit[EnkiEpuck::ir_count] = {};
    uint16_t acceleration[3] = { 0, 0, 0 };
    // Where the microphones are during this step, and how they hear the
    // sound sources from there.
    std::array<Enki::Point, microphone_places.size()> microphones;
    std::array<std::vector<Hearing>, microphone_places.size()> hearings;
    uint16_t selector = 0;
    RemoteReceiver remote;
    Battery battery{ BatteryModel{}, 1 };
};

namespace
{

using RobotState = EnkiWorld::RobotState;

RobotState &state_of(void *context)
{
    return *static_cast<RobotState *>(context);
}

double clamp_adc(double value)
{
    return std::clamp(std::round(value), 0.0, adc_maximum);
}

uint16_t world_adc_read(void *context, uint8_t channel, uint64_t cycle)
{
    RobotState &state = state_of(context);
    if (channel >= EPUCK_ADC_PROXIMITY_0) {
        unsigned sensor = channel - EPUCK_ADC_PROXIMITY_0;
        epuck_pin emitter = epuck_pin(EPUCK_PIN_IR_PULSE_0_4 + sensor % 4);
        return state.output[emitter] ? state.proximity_lit[sensor] : HOST_FLAT_PROXIMITY;
    }
    if (channel >= EPUCK_ADC_ACCELEROMETER_X && channel <= EPUCK_ADC_ACCELEROMETER_Z)
        return state.acceleration[channel - EPUCK_ADC_ACCELEROMETER_X];
    if (channel >= EPUCK_ADC_MICROPHONE_0 && channel < EPUCK_ADC_ACCELEROMETER_X) {
        const SoundField &field = state.world->sound_field();
        if (field.silent())
            return HOST_FLAT_MICROPHONE;
        return field.reading(state.hearings[channel - EPUCK_ADC_MICROPHONE_0],
                             double(cycle) / HOST_CYCLES_PER_SECOND);
    }
    return HOST_FLAT_OTHER_INPUT;
}

// Apart from world_adc_read_channels, so that a silent arena's microphones
// cost no saving of the registers this loop needs.
[[gnu::noinline]] void adc_read_one_by_one(void *context,
                                           uint16_t channel_mask,
                                           uint64_t cycle,
                                           uint16_t *values)
{
    for (unsigned count = 0; channel_mask != 0; channel_mask &= uint16_t(channel_mask - 1))
        values[count++] = world_adc_read(context, uint8_t(__builtin_ctz(channel_mask)), cycle);
}

void world_adc_read_channels(void *context, uint16_t channel_mask, uint64_t cycle, uint16_t *values)
{
    RobotState &state = state_of(context);
    // Most scans convert the microphones alone: in a silent arena they hear
    // the bias, whatever the time.
    if (channel_mask == microphone_channels && state.world->sound_field().silent()) {
        std::fill(values, values + microphone_count, uint16_t(HOST_FLAT_MICROPHONE));
        return;
    }
    adc_read_one_by_one(context, channel_mask, cycle, values);
}

bool world_adc_channels_steady(void *context, uint16_t channel_mask)
{
    // In a silent arena the microphones hear the bias at every cycle; the
    // other inputs change with the world's steps and the emitters.
    return channel_mask == microphone_channels && state_of(context).world->sound_field().silent();
}

bool world_pin_read(void *context, epuck_pin pin, uint64_t cycle)
{
    RobotState &state = state_of(context);
    switch (pin) {
    case EPUCK_PIN_SELECTOR_0:
    case EPUCK_PIN_SELECTOR_1:
    case EPUCK_PIN_SELECTOR_2:
    case EPUCK_PIN_SELECTOR_3:
        // ⚠ The selector's polarity is not documented (§3.8): a 1 bit reads
        // high, as the library and our driver take it.
        return (state.selector >> (pin - EPUCK_PIN_SELECTOR_0)) & 1u;
    case EPUCK_PIN_BATTERY_LOW: return !state.battery.low();
    case EPUCK_PIN_REMOTE: return state.remote.level(cycle);
    default: return false; // the camera's lines are idle
    }
}

// Apart from world_inputs_read, so that the selector's bits cost no saving
// of the registers this loop needs.
[[gnu::noinline]] uint16_t inputs_read_one_by_one(void *context,
                                                  epuck_pin first,
                                                  uint8_t count,
                                                  uint64_t cycle)
{
    uint16_t levels = 0;
    for (uint8_t i = 0; i < count; i++)
        if (world_pin_read(context, epuck_pin(first + i), cycle))
            levels |= uint16_t(1u << i);
    return levels;
}

uint16_t world_inputs_read(void *context, epuck_pin first, uint8_t count, uint64_t cycle)
{
    // The selector's bits, which the firmware reads every millisecond, at
    // once.
    if (first == EPUCK_PIN_SELECTOR_0 && count == selector_bits)
        return state_of(context).selector & (selector_positions - 1u);
    return inputs_read_one_by_one(context, first, count, cycle);
}

uint64_t world_next_input_change(void *context, uint64_t after_cycle)
{
    uint64_t change = state_of(context).remote.next_change(after_cycle);
    return change == UINT64_MAX ? HOST_NO_INPUT_CHANGE : change;
}

// How many motors have their coils powered (the driver powers none at speed 0).
unsigned motors_turning(const RobotState &state)
{
    unsigned turning = 0;
    for (epuck_pin first : { EPUCK_PIN_MOTOR_LEFT_A, EPUCK_PIN_MOTOR_RIGHT_A })
        for (int line = 0; line < phase_count; line++)
            if (state.output[first + line]) {
                turning++;
                break;
            }
    return turning;
}

// Which phase index each pattern of a motor's lines (bit 3 = A .. bit 0 =
// D) shows; -1: none (coils off, or half-way through writing the lines).
constexpr std::array<int8_t, 16> phase_of_pattern = [] {
    std::array<int8_t, 16> table{};
    table.fill(-1);
    for (int index = 0; index < phase_count; index++)
        table[phase_patterns[index]] = int8_t(index);
    return table;
}();

// A motor's phase lines changed: when they show the next pattern of the
// sequence, or the one before, the motor made a step.
void phase_written(RobotState &state, Motor motor)
{
    const int index = phase_of_pattern[state.lines[motor]];
    if (index < 0)
        return;
    // Indices 0..3: the change forward, modulo 4.
    static_assert(phase_count == 4);
    int change = (index - state.phase[motor]) & (phase_count - 1);
    state.phase[motor] = index;
    // The motors are mirror-mounted: forward steps the left motor's phase
    // index down and the right motor's up (§3.6). A jump of two is no step.
    int up = change == 1 ? 1 : change == phase_count - 1 ? -1 : 0;
    state.steps[motor] += motor == left_motor ? -up : up;
}

void world_pin_written(void *context, epuck_pin pin, bool high, uint64_t)
{
    RobotState &state = state_of(context);
    // A line driven as it was changes nothing: the lines' pattern was seen
    // when it was last written.
    if (state.output[pin] == high)
        return;
    state.output[pin] = high;
    static_assert(EPUCK_PIN_MOTOR_LEFT_D == EPUCK_PIN_MOTOR_LEFT_A + phase_count - 1 &&
                  EPUCK_PIN_MOTOR_RIGHT_D == EPUCK_PIN_MOTOR_RIGHT_A + phase_count - 1);
    unsigned line = unsigned(pin) - EPUCK_PIN_MOTOR_LEFT_A;
    Motor motor = left_motor;
    if (line >= phase_count) {
        line = unsigned(pin) - EPUCK_PIN_MOTOR_RIGHT_A;
        motor = right_motor;
        if (line >= phase_count)
            return;
    }
    state.lines[motor] ^= uint8_t(8u >> line);
    phase_written(state, motor);
}

bool world_i2c_write(void *context,
                     uint8_t device,
                     uint8_t reg,
                     const uint8_t *bytes,
                     uint16_t count)
{
    RobotState &state = state_of(context);
    if (device != EPUCK_I2C_CAMERA_ADDRESS)
        return false;
    for (uint16_t i = 0; i < count; i++)
        state.camera_registers[uint8_t(reg + i)] = bytes[i];
    return true;
}

bool world_i2c_read(void *context, uint8_t device, uint8_t reg, uint8_t *bytes, uint16_t count)
{
    RobotState &state = state_of(context);
    if (device != EPUCK_I2C_CAMERA_ADDRESS)
        return false;
    state.camera_registers[0] = camera_id_high;
    state.camera_registers[1] = camera_id_low;
    for (uint16_t i = 0; i < count; i++)
        bytes[i] = state.camera_registers[uint8_t(reg + i)];
    return true;
}

// std::lround of a non-negative level below 2^32 (a colour's 0..63, a
// proximity reading's 0..65535), without the library call (a row of pixels
// takes 360 of them, the proximity sensors 800 a robot-second): the
// fraction of a non-negative double is exact, so the comparison rounds
// halves up as lround does.
unsigned rounded_level(double level)
{
    auto whole = unsigned(level);
    return level - whole >= 0.5 ? whole + 1 : whole;
}

// A pixel's RGB565 bytes, high byte first (hardware §3.5), into `bytes`.
void rgb565_bytes(const Color &color, uint8_t *bytes)
{
    unsigned red = rounded_level(color.red * rgb565_red_levels);
    unsigned green = rounded_level(color.green * rgb565_green_levels);
    unsigned blue = rounded_level(color.blue * rgb565_blue_levels);
    uint16_t word = uint16_t(red << 11 | green << 5 | blue);
    bytes[0] = uint8_t(word >> 8);
    bytes[1] = uint8_t(word & 0xFF);
}

uint8_t world_camera_byte(void *context, uint16_t row, uint16_t index, uint64_t)
{
    RobotState &state = state_of(context);
    if (index >= camera_row_bytes)
        return 0;
    if (state.rendered_step != state.world->steps() || state.rendered_row != row) {
        Color pixels[camera_row_pixels];
        state.world->camera_row(state.index, row, pixels);
        for (unsigned pixel = 0; pixel < camera_row_pixels; pixel++)
            rgb565_bytes(pixels[pixel], &state.row_bytes[2 * pixel]);
        state.rendered_step = state.world->steps();
        state.rendered_row = row;
    }
    return state.row_bytes[index];
}

void world_camera_every_second_pixel(void *context,
                                     uint16_t row,
                                     uint16_t pixels,
                                     uint64_t,
                                     uint8_t *bytes)
{
    // The bytes world_camera_byte gives, of the pixels read only: the row's
    // pixels are worked out one by one, each the same alone.
    RobotState &state = state_of(context);
    Color colors[camera_row_pixels];
    state.world->camera_row(state.index, row, colors, 2);
    // Neighbouring pixels mostly see the same floor, area or body: a pixel
    // of the colour before it takes that pixel's bytes, not three roundings.
    const Color *previous = nullptr;
    for (unsigned pixel = 0; pixel < pixels; pixel++) {
        uint8_t *pixel_bytes = bytes + 2 * pixel;
        if (2 * pixel < camera_row_pixels) {
            const Color &color = colors[2 * pixel];
            if (previous != nullptr && color.red == previous->red &&
                color.green == previous->green && color.blue == previous->blue) {
                pixel_bytes[0] = pixel_bytes[-2];
                pixel_bytes[1] = pixel_bytes[-1];
            } else {
                rgb565_bytes(color, pixel_bytes);
            }
            previous = &color;
        } else {
            pixel_bytes[0] = 0;
            pixel_bytes[1] = 0;
        }
    }
}

Color from_enki(const Enki::Color &color)
{
    return { std::clamp(color.r(), 0.0, 1.0),
             std::clamp(color.g(), 0.0, 1.0),
             std::clamp(color.b(), 0.0, 1.0) };
}

Enki::Color to_enki(const Color &color)
{
    return Enki::Color(color.red, color.green, color.blue);
}

size_t aligned(size_t bytes)
{
    constexpr size_t alignment = __STDCPP_DEFAULT_NEW_ALIGNMENT__;
    return (bytes + alignment - 1) / alignment * alignment;
}

} // namespace

FreshIRSensor::FreshIRSensor(Enki::Robot *robot,
                             Enki::Vector position,
                             double sensor_height,
                             double heading,
                             double reach,
                             double response_maximum,
                             double response_x0,
                             double response_c,
                             double noise_sd)
  : Enki::IRSensor(robot,
                   position,
                   sensor_height,
                   heading,
                   reach,
                   response_maximum,
                   response_x0,
                   response_c,
                   noise_sd)
{
    for (unsigned i = 0; i < ray_count; i++) {
        double angle = heading + rayAngles.at(i);
        ray_directions_[i] = Enki::Vector(std::cos(angle), std::sin(angle));
    }
}

void FreshIRSensor::init(double, Enki::World *)
{
    start_step(Enki::Matrix22(owner->angle));
}

void FreshIRSensor::start_step(const Enki::Matrix22 &owner_rotation)
{
    // Debian's IRSensor::init, operation for operation (the same values
    // bit for bit), with the rotation given.
    absPos = owner->pos + owner_rotation * pos;
    absOrientation = owner->angle + orientation;
    absSmartPos = owner_rotation * smartPos + absPos;
    for (unsigned i = 0; i < ray_count; i++) {
        rayDists[i] = range;
        // Debian's Enki forgets this (upstream fix 7dbaa0b): without it a
        // ray that meets nothing this step keeps last step's value.
        rayValues[i] = 0.0;
        absRayAngles[i] = absOrientation + rayAngles[i];
        world_ray_directions_[i] = owner_rotation * ray_directions_[i];
    }
}

namespace
{
// Constant-initialised: no guard at each use.
constinit thread_local IrNoise thread_ir_noise;
} // namespace

IrNoise &ir_noise()
{
    return thread_ir_noise;
}

void seed_ir_noise(uint32_t seed)
{
    thread_ir_noise.reseed(seed);
}

void FreshIRSensor::finalize(double, Enki::World *)
{
    // Debian's IRSensor::finalize operation for operation (its machine
    // code: the three rays' sum, then Enki's gaussianRand(sum, noiseSd),
    // clamped to 0..m), with rand() from ir_noise().
    IrNoise &noise = thread_ir_noise;
    const double sum = rayValues[0] + rayValues[1] + rayValues[2];
    double x, y, squared;
    do {
        x = double(noise.next()) / IrNoise::maximum * 2 - 1;
        y = double(noise.next()) / IrNoise::maximum * 2 - 1;
        squared = x * x + y * y;
    } while (squared > 1.0 || squared == 0);
    double value = noiseSd * y * std::sqrt(-2.0 * std::log(squared) / squared) + sum;
    value = value < m ? value : m;
    finalValue = value > 0 ? value : 0;
    finalDist = inverseResponseFunction(finalValue);
}

void FreshIRSensor::objectStep(double dt, Enki::World *world, Enki::PhysicalObject *object)
{
    if (height > object->getHeight())
        return;
    see(dt, world, object, object->getRadius(), object->isCylindric());
}

inline void FreshIRSensor::see(double dt,
                               Enki::World *world,
                               Enki::PhysicalObject *object,
                               double radius,
                               bool cylindric)
{
    // Debian's IRSensor::objectStep for boxes; for cylinders, the same
    // geometry without its trigonometry (see enki_world.hpp). The object
    // is as tall as the sensor or taller.
    // The object's bounding circle beyond the circle around the rays.
    const Enki::Vector from_rays_middle = object->pos - absSmartPos;
    const double radius_sum = radius + smartRadius;
    if (from_rays_middle.norm2() > radius_sum * radius_sum)
        return;
    const Enki::Vector to_centre = object->pos - absPos;
    const double squared_radius = radius * radius;
    if (!cylindric) {
        // A box (the obstacles, few): Enki's polygon test, for the rays
        // whose line passes within the bounding circle (a margin of 1e-6
        // of it wider than the difference between the cross product and
        // Enki's arc tangent and sine, about 1e-13 at these distances).
        const double reach_squared = squared_radius * (1 + 1e-6) + 1e-9;
        for (unsigned i = 0; i < ray_count; i++) {
            const Enki::Vector &direction = world_ray_directions_[i];
            double across = direction.x * to_centre.y - direction.y * to_centre.x;
            if (across * across <= reach_squared) {
                Enki::IRSensor::objectStep(dt, world, object);
                return;
            }
        }
        return;
    }
    // A ray's line passes at `across` from the circle's centre (the cross
    // product with its unit direction) and meets the circle at `along` (the
    // dot product: Enki's sqrt(|v|^2 - across^2)) less the half chord. As
    // in Enki, the line goes both ways from the sensor.
    for (unsigned i = 0; i < ray_count; i++) {
        const Enki::Vector &direction = world_ray_directions_[i];
        const double across = direction.x * to_centre.y - direction.y * to_centre.x;
        const double across_squared = across * across;
        if (across_squared <= squared_radius) {
            const double along = std::abs(direction.x * to_centre.x + direction.y * to_centre.y);
            update_ray(i, std::max(along - std::sqrt(squared_radius - across_squared), 0.));
        }
    }
}

void FreshIRSensor::wallsStep(double dt, Enki::World *world)
{
    if (world->wallsType != Enki::World::WALLS_SQUARE) {
        Enki::IRSensor::wallsStep(dt, world);
        return;
    }
    // Debian's IRSensor::wallsStep for square walls, with the rays'
    // directions of this step instead of a sine and cosine a ray (the
    // same up to rounding). Nothing while the circle around the rays is
    // inside the walls.
    if (absSmartPos.x - smartRadius > 0 && absSmartPos.y - smartRadius > 0 &&
        absSmartPos.x + smartRadius < world->w && absSmartPos.y + smartRadius < world->h)
        return;
    if (absPos.x < 0 || absPos.x > world->w || absPos.y < 0 || absPos.y > world->h) {
        // The sensor in a wall: Enki gives every ray the distance m (its
        // response's maximum) and no value.
        std::fill(rayDists.begin(), rayDists.end(), m);
        std::fill(rayValues.begin(), rayValues.end(), 0.0);
        return;
    }
    for (unsigned i = 0; i < ray_count; i++) {
        // Where the ray, as long as the range, leaves through the walls it
        // crosses, as a fraction of its length.
        const Enki::Point end = absPos + world_ray_directions_[i] * range;
        double through_x = HUGE_VAL, through_y = HUGE_VAL;
        if (end.x < 0)
            through_x = -absPos.x / (end.x - absPos.x);
        else if (end.x > world->w)
            through_x = (world->w - absPos.x) / (end.x - absPos.x);
        if (end.y < 0)
            through_y = -absPos.y / (end.y - absPos.y);
        else if (end.y > world->h)
            through_y = (world->h - absPos.y) / (end.y - absPos.y);
        update_ray(i, std::min(through_x, through_y) * range);
    }
}

void FreshIRSensor::update_ray(unsigned ray, double distance)
{
    // Debian's IRSensor::updateRay, operation for operation.
    if (!(distance < rayDists[ray]))
        return;
    rayDists[ray] = distance;
    rayValues[ray] = response(distance);
    if (ray == 1)
        rayValues[ray] -= 2 * response(distance * alpha);
}

double FreshIRSensor::response(double distance) const
{
    // Enki's response m (c - x0^2) / (x^2 - 2 x0 x + c), m below x0 and 0
    // beyond the range, in Enki's operation order.
    if (distance < x0)
        return m;
    if (distance > range)
        return 0;
    return m * (c - x0 * x0) / (distance * distance - 2 * x0 * distance + c);
}

namespace
{
FreshIRSensor make_ir(Enki::Robot *owner, unsigned i)
{
    const IrPlacement &place = ir_placements[i];
    return FreshIRSensor(owner,
                         Enki::Vector(place.x, place.y),
                         ir_height,
                         place.heading_degrees * radians_per_degree,
                         ir_range,
                         ir_response_maximum,
                         ir_response_x0,
                         ir_response_c,
                         ir_noise_sd);
}

// Whether some rows of the window look above the horizon, where Enki's
// camera (costly) is needed; below it our own ray casting does the work.
bool camera_looks_above_horizon(double tilt_degrees)
{
    return tilt_degrees * radians_per_degree < camera_vertical_field / 2;
}

} // namespace

EnkiEpuck::EnkiEpuck(double wheel_noise, double camera_half_field_radians, bool camera_used)
  : DifferentialWheeled(wheel_distance, wheel_speed_limit, wheel_noise)
  , infrared{ { make_ir(this, 0),
                make_ir(this, 1),
                make_ir(this, 2),
                make_ir(this, 3),
                make_ir(this, 4),
                make_ir(this, 5),
                make_ir(this, 6),
                make_ir(this, 7) } }
  , camera(this,
           Enki::Vector(camera_forward, 0),
           camera_height,
           0,
           camera_half_field_radians,
           camera_pixels)
{
    for (FreshIRSensor &sensor : infrared)
        addLocalInteraction(&sensor);
    if (camera_used)
        addLocalInteraction(&camera);
    setCylindric(body_radius, body_height, body_mass);
    setColor(body_color);
}

void EnkiEpuck::initLocalInteractions(double dt, Enki::World *world)
{
    // Each sensor is independent: the order of their starts does not matter.
    const Enki::Matrix22 rotation(angle);
    for (FreshIRSensor &sensor : infrared)
        sensor.start_step(rotation);
    if (sensor_count() > ir_count)
        camera.init(dt, world);
}

void EnkiEpuck::doLocalInteractions(double dt, Enki::World *world, Enki::PhysicalObject *object)
{
    // Robot::doLocalInteractions in its arithmetic: the interactions in
    // Enki's order (longest reach first) while the object is within reach;
    // the object's size and shape read once for the IR sensors.
    const Enki::Vector from_object(pos.x - object->pos.x, pos.y - object->pos.y);
    const double distance_squared = from_object.norm2();
    const double radius = object->getRadius();
    const bool ir_sees = !(ir_height > object->getHeight());
    const bool cylindric = object->isCylindric();
    for (Enki::LocalInteraction *interaction : localInteractions) {
        const double reach = interaction->getRange() + radius;
        if (!(distance_squared < reach * reach))
            return;
        if (interaction == &camera)
            interaction->objectStep(dt, world, object);
        else if (ir_sees)
            static_cast<FreshIRSensor *>(interaction)->see(dt, world, object, radius, cylindric);
    }
}

void EnkiEpuck::applyForces(double dt)
{
    // The wheels set the velocity; remember it to see what collisions change.
    DifferentialWheeled::applyForces(dt);
    commanded_velocity_ = speed;
}

void EnkiEpuck::collisionEvent(Enki::PhysicalObject *)
{
    collisions_this_step_++;
}

void EnkiEpuck::controlStep(double dt)
{
    // Enki clears the depth in the parent's controlStep: read it first.
    collision_depth = getInterlacedDistance();
    collisions = collisions_this_step_;
    collisions_this_step_ = 0;
    bool touching = collisions > 0;
    // Only the start of a contact is an impact: a robot pushing on a wall
    // stalls, it does not keep bouncing.
    impact = touching && !touching_ ? (speed - commanded_velocity_) / dt : Enki::Vector();
    touching_ = touching;
    DifferentialWheeled::controlStep(dt);
}

uint16_t proximity_lit_reading(double enki_value, uint16_t ambient)
{
    // Enki's response was fitted to real e-puck readings (reflected light,
    // 0..3731): the lit reading is that much below the ambient one.
    double reflected = std::clamp(enki_value, 0.0, double(ambient));
    return uint16_t(rounded_level(double(ambient) - reflected));
}

uint16_t accelerometer_reading(unsigned axis, double forward, double leftward)
{
    double g;
    switch (axis) {
    case 0: g = -leftward / gravity; break; // +X = right
    case 1: g = -forward / gravity; break;  // +Y = backward
    default: g = 1; break;                  // upright
    }
    return uint16_t(clamp_adc(zero_g_counts + g * counts_per_g));
}

EnkiWorld::EnkiWorld(const Arena &arena, uint32_t seed)
  : arena_(arena)
  , sound_field_(arena.sounds)
{
    world_ =
      std::make_unique<PartitionedWorld>(arena.width, arena.height, to_enki(arena.wall_color));
    world_->takeObjectOwnership = false;
    world_->setRandomSeed(seed);
    seed_ir_noise(seed); // where Enki's IR sensors draw from rand()

    size_t robots_bytes = aligned(arena.robots.size() * sizeof(EnkiEpuck));
    size_t total = robots_bytes + arena.obstacles.size() * sizeof(Enki::PhysicalObject);
    objects_block_ = ::operator new(std::max<size_t>(total, 1));
    auto *robot_memory = static_cast<EnkiEpuck *>(objects_block_);
    auto *obstacle_memory =
      reinterpret_cast<Enki::PhysicalObject *>(static_cast<char *>(objects_block_) + robots_bytes);

    for (size_t i = 0; i < arena.robots.size(); i++) {
        const RobotPlacement &place = arena.robots[i];
        EnkiEpuck *robot =
          new (robot_memory + i) EnkiEpuck(arena.wheel_noise,
                                           camera_horizontal_field / 2,
                                           camera_looks_above_horizon(arena.camera_tilt_degrees));
        robot->pos = Enki::Point(place.x, place.y);
        robot->angle = place.heading_degrees * radians_per_degree;
        robot->camera.setRange(camera_horizon_range);
        robots_.push_back(robot);
        world_->addObject(robot);

        auto state = std::make_unique<RobotState>();
        state->world = this;
        state->index = i;
        state->table = { state.get(),
                         world_adc_read,
                         world_pin_read,
                         world_pin_written,
                         world_i2c_write,
                         world_i2c_read,
                         world_camera_byte,
                         world_next_input_change,
                         world_adc_read_channels,
                         world_adc_channels_steady,
                         world_camera_every_second_pixel,
                         world_inputs_read,
                         true };
        state->selector = place.selector;
        state->battery = Battery(arena.battery, place.battery_charge);
        place_microphones(*state);
        states_.push_back(std::move(state));
    }
    // Before the first step: no reflection, no impact.
    for (auto &state : states_) {
        std::fill(std::begin(state->proximity_lit),
                  std::end(state->proximity_lit),
                  uint16_t(HOST_FLAT_PROXIMITY));
        for (unsigned axis = 0; axis < 3; axis++)
            state->acceleration[axis] = accelerometer_reading(axis, 0, 0);
    }
    for (size_t i = 0; i < arena.obstacles.size(); i++) {
        const Obstacle &obstacle = arena.obstacles[i];
        auto *object = new (obstacle_memory + i) Enki::PhysicalObject;
        if (obstacle.shape == Obstacle::Shape::box)
            object->setRectangular(obstacle.length, obstacle.width, obstacle_height, static_mass);
        else
            object->setCylindric(obstacle.radius, obstacle_height, static_mass);
        object->setColor(to_enki(obstacle.color));
        object->pos = Enki::Point(obstacle.x, obstacle.y);
        object->angle = obstacle.heading_degrees * radians_per_degree;
        obstacles_.push_back(object);
        world_->addObject(object);

        Occluder occluder;
        occluder.box = obstacle.shape == Obstacle::Shape::box;
        occluder.centre = Enki::Point(obstacle.x, obstacle.y);
        occluder.half_length = obstacle.length / 2;
        occluder.half_width = obstacle.width / 2;
        const double heading = obstacle.heading_degrees * radians_per_degree;
        occluder.cosine = std::cos(heading);
        occluder.sine = std::sin(heading);
        occluder.radius =
          occluder.box ? std::hypot(occluder.half_length, occluder.half_width) : obstacle.radius;
        occluder.color = obstacle.color;
        obstacle_occluders_.push_back(occluder);
    }
    build_robot_grid();
}

EnkiWorld::~EnkiWorld()
{
    world_.reset();
    for (EnkiEpuck *robot : robots_)
        robot->~EnkiEpuck();
    for (Enki::PhysicalObject *object : obstacles_)
        object->~PhysicalObject();
    ::operator delete(objects_block_);
}

size_t EnkiWorld::robot_count() const
{
    return robots_.size();
}

const host_world *EnkiWorld::world_of(size_t index) const
{
    return &states_.at(index)->table;
}

EnkiEpuck &EnkiWorld::robot(size_t index)
{
    return *robots_.at(index);
}

void EnkiWorld::set_parallel_for(PartitionedWorld::ParallelFor parallel_for)
{
    parallel_for_ = parallel_for;
    world_->set_parallel_for(std::move(parallel_for));
}

void EnkiWorld::build_robot_grid()
{
    robot_cell_size_ = camera_cell_size;
    robot_columns_ = std::max(1L, long(std::ceil(arena_.width / robot_cell_size_)));
    robot_rows_ = std::max(1L, long(std::ceil(arena_.height / robot_cell_size_)));
    auto cell_of = [this](double at, long count) {
        return long(std::clamp(std::floor(at / robot_cell_size_), 0.0, double(count - 1)));
    };
    // Counting sort of the robots by cell, ascending within.
    robot_cell_starts_.assign(size_t(robot_columns_ * robot_rows_) + 1, 0);
    robot_cells_.resize(robots_.size());
    thread_local std::vector<uint32_t> cells;
    cells.resize(robots_.size());
    for (size_t i = 0; i < robots_.size(); i++) {
        const Enki::Point &at = robots_[i]->pos;
        cells[i] =
          uint32_t(cell_of(at.y, robot_rows_) * robot_columns_ + cell_of(at.x, robot_columns_));
        robot_cell_starts_[cells[i] + 1]++;
    }
    for (size_t c = 1; c < robot_cell_starts_.size(); c++)
        robot_cell_starts_[c] += robot_cell_starts_[c - 1];
    thread_local std::vector<uint32_t> fill;
    fill.assign(robot_cell_starts_.begin(), robot_cell_starts_.end() - 1);
    for (size_t i = 0; i < robots_.size(); i++)
        robot_cells_[fill[cells[i]]++] = uint32_t(i);
}

void EnkiWorld::step()
{
    for (size_t i = 0; i < robots_.size(); i++) {
        RobotState &state = *states_[i];
        state.battery.drain(step_seconds, motors_turning(state));
        state.remote.forget_before(cycles());
        for (int motor : { left_motor, right_motor }) {
            state.wheel_speed[motor] = state.steps[motor] * centimetres_per_step / step_seconds;
            state.steps[motor] = 0;
        }
        robots_[i]->leftSpeed = state.wheel_speed[left_motor];
        robots_[i]->rightSpeed = state.wheel_speed[right_motor];
    }
    world_->step(step_seconds);
    // Each robot's readings from its own body and state alone: the robots
    // may be shared out among threads.
    auto read_robots = [this](size_t begin, size_t end) {
        for (size_t i = begin; i < end; i++)
            read_robot(i);
    };
    if (parallel_for_)
        parallel_for_(robots_.size(), read_robots);
    else
        read_robots(0, robots_.size());
    build_robot_grid();
    steps_++;
}

void EnkiWorld::read_robot(size_t i)
{
    RobotState &state = *states_[i];
    Enki::Vector impact = robots_[i]->impact;
    double period = shock_period_at(robots_[i]->pos);
    state.shock_clock = period > 0 ? state.shock_clock + step_seconds : 0;
    if (period > 0 && state.shock_clock >= period - step_seconds / 2) {
        state.shock_clock = 0;
        double heading = robots_[i]->angle;
        impact = Enki::Vector(std::cos(heading), std::sin(heading)) * -knock_acceleration;
    }
    if (impact.x != 0 || impact.y != 0) {
        state.impact = impact;
        state.impact_steps_left = impact_steps;
    } else if (state.impact_steps_left > 0 && --state.impact_steps_left == 0) {
        state.impact = Enki::Vector();
    }
    update_readings(state);
}

void EnkiWorld::update_readings(RobotState &state)
{
    const EnkiEpuck &robot = *robots_[state.index];
    for (unsigned sensor = 0; sensor < EnkiEpuck::ir_count; sensor++)
        state.proximity_lit[sensor] =
          proximity_lit_reading(robot.infrared[sensor].getValue(), HOST_FLAT_PROXIMITY);
    Enki::Vector forward_axis(std::cos(robot.angle), std::sin(robot.angle));
    double forward = state.impact * forward_axis;
    double leftward = state.impact * forward_axis.perp();
    for (unsigned axis = 0; axis < 3; axis++)
        state.acceleration[axis] = accelerometer_reading(axis, forward, leftward);
    place_microphones(state);
}

void EnkiWorld::place_microphones(RobotState &state)
{
    const EnkiEpuck &robot = *robots_[state.index];
    Enki::Vector forward(std::cos(robot.angle), std::sin(robot.angle));
    for (size_t i = 0; i < microphone_places.size(); i++) {
        state.microphones[i] = robot.pos + forward * microphone_places[i].forward +
                               forward.perp() * microphone_places[i].left;
        sound_field_.hear(state.microphones[i].x, state.microphones[i].y, state.hearings[i]);
    }
}

uint64_t EnkiWorld::cycles() const
{
    return steps_ * step_cycles;
}

void EnkiWorld::set_selector(size_t index, uint16_t position)
{
    states_.at(index)->selector = uint16_t(position & (selector_positions - 1));
}

uint16_t EnkiWorld::selector(size_t index) const
{
    return states_.at(index)->selector;
}

void EnkiWorld::send_rc5(size_t index, const Rc5Frame &frame)
{
    states_.at(index)->remote.send(frame, cycles());
}

const Battery &EnkiWorld::battery(size_t index) const
{
    return states_.at(index)->battery;
}

double EnkiWorld::shock_period_at(const Enki::Point &point) const
{
    // The shortest period of the shock areas under the robot's centre.
    double period = 0;
    for (const GroundArea &area : arena_.areas)
        if (area.shock_period > 0 && area.contains(point.x, point.y))
            period = period > 0 ? std::min(period, area.shock_period) : area.shock_period;
    return period;
}

Pose EnkiWorld::pose(size_t index) const
{
    const EnkiEpuck &robot = *robots_.at(index);
    return { robot.pos.x, robot.pos.y, robot.angle };
}

void EnkiWorld::place(size_t index, const Pose &pose)
{
    EnkiEpuck &robot = *robots_.at(index);
    robot.pos = Enki::Point(pose.x, pose.y);
    robot.angle = pose.heading;
    place_microphones(*states_.at(index));
    build_robot_grid();
}

double EnkiWorld::left_wheel_speed(size_t index) const
{
    return states_.at(index)->wheel_speed[left_motor];
}

double EnkiWorld::right_wheel_speed(size_t index) const
{
    return states_.at(index)->wheel_speed[right_motor];
}

namespace
{

using Occluder = EnkiWorld::Occluder;

constexpr double no_hit = HUGE_VAL;

// Where along the ray from `from` in unit direction `direction` it enters
// the occluder (0 when it starts inside), or no_hit.
double ray_entry(const Occluder &occluder, const Enki::Point &from, const Enki::Vector &direction)
{
    Enki::Vector to_centre = occluder.centre - from;
    if (!occluder.box) {
        double along = to_centre * direction;
        double outside = to_centre.norm2() - occluder.radius * occluder.radius;
        if (outside <= 0)
            return 0;
        double discriminant = along * along - outside;
        if (along <= 0 || discriminant < 0)
            return no_hit;
        return along - std::sqrt(discriminant);
    }
    // A box: the slab test in the box's own frame.
    const double c = occluder.cosine, s = occluder.sine;
    double start[2] = { -(to_centre.x * c + to_centre.y * s),
                        -(-to_centre.x * s + to_centre.y * c) };
    double step[2] = { direction.x * c + direction.y * s, -direction.x * s + direction.y * c };
    double half[2] = { occluder.half_length, occluder.half_width };
    double enter = -no_hit, leave = no_hit;
    for (int axis = 0; axis < 2; axis++) {
        if (step[axis] == 0) {
            if (std::abs(start[axis]) > half[axis])
                return no_hit;
            continue;
        }
        double t1 = (-half[axis] - start[axis]) / step[axis];
        double t2 = (half[axis] - start[axis]) / step[axis];
        enter = std::max(enter, std::min(t1, t2));
        leave = std::min(leave, std::max(t1, t2));
    }
    if (enter > leave || leave < 0)
        return no_hit;
    return std::max(enter, 0.0);
}

// Where the ray leaves the arena through a wall.
double wall_distance(const Arena &arena, const Enki::Point &from, const Enki::Vector &direction)
{
    double distance = no_hit;
    if (direction.x > 0)
        distance = std::min(distance, (arena.width - from.x) / direction.x);
    if (direction.x < 0)
        distance = std::min(distance, -from.x / direction.x);
    if (direction.y > 0)
        distance = std::min(distance, (arena.height - from.y) / direction.y);
    if (direction.y < 0)
        distance = std::min(distance, -from.y / direction.y);
    return std::max(distance, 0.0);
}

} // namespace

namespace
{

// Each camera pixel's ray relative to the robot's heading, left edge (+28°)
// to right edge (-28°) at the pixel's centre, as a unit vector: computed
// once, then turned by the heading, which saves two trigonometric calls
// per pixel. Turning instead of adding angles moves a ray by about 1e-16
// rad: a pixel can change only where its ray meets an edge that exactly.
using PixelRays = std::array<Enki::Vector, camera_row_pixels>;
const PixelRays &pixel_rays()
{
    static const PixelRays rays = [] {
        PixelRays table;
        for (unsigned pixel = 0; pixel < camera_row_pixels; pixel++) {
            double angle = camera_horizontal_field / 2 -
                           (double(pixel) + 0.5) * camera_horizontal_field / camera_row_pixels;
            table[pixel] = Enki::Vector(std::cos(angle), std::sin(angle));
        }
        return table;
    }();
    return rays;
}

} // namespace

void EnkiWorld::camera_row(size_t index, unsigned row, Color *pixels, unsigned pixel_step) const
{
    const EnkiEpuck &robot = *robots_.at(index);
    // How far below the horizon the row looks.
    double row_centre = (double(std::min(row, camera_window_rows - 1u)) + 0.5) / camera_window_rows;
    double depression =
      arena_.camera_tilt_degrees * radians_per_degree + (row_centre - 0.5) * camera_vertical_field;
    if (depression <= 0) {
        // Above the horizon: what Enki's camera sees. Enki's pixel 0 is the
        // rightmost, the window's pixel 0 the leftmost.
        for (unsigned pixel = 0; pixel < camera_row_pixels; pixel += pixel_step) {
            unsigned enki_pixel =
              EnkiEpuck::camera_pixels - 1 - pixel * EnkiEpuck::camera_pixels / camera_row_pixels;
            pixels[pixel] = from_enki(robot.camera.image[enki_pixel]);
        }
        return;
    }
    // Below: the floor at `reach`, unless a robot, obstacle or wall stands
    // nearer on the pixel's ray (all are taller than the camera).
    double reach = camera_height / std::tan(depression);
    Enki::Vector forward(std::cos(robot.angle), std::sin(robot.angle));
    Enki::Point lens = robot.pos + forward * camera_forward;
    // The robots and obstacles that may stand nearer than the floor, in
    // arena order (robots by index, then obstacles): the nearest wins, the
    // first of a tie.
    thread_local std::vector<uint32_t> candidates;
    thread_local std::vector<Occluder> near;
    candidates.clear();
    near.clear();
    const double robot_reach = reach + body_radius;
    auto cell_of = [this](double at, long count) {
        return long(std::clamp(std::floor(at / robot_cell_size_), 0.0, double(count - 1)));
    };
    // A robot's centre lies in its cell, or in the border cell nearest to
    // it when pushed past a wall: either way within the cells around the
    // lens's reach when it is within that reach (clamped before becoming
    // whole: a row just below the horizon reaches very far).
    const long x0 = cell_of(lens.x - robot_reach, robot_columns_);
    const long x1 = cell_of(lens.x + robot_reach, robot_columns_);
    const long y0 = cell_of(lens.y - robot_reach, robot_rows_);
    const long y1 = cell_of(lens.y + robot_reach, robot_rows_);
    for (long y = y0; y <= y1; y++)
        for (long x = x0; x <= x1; x++) {
            const size_t cell = size_t(y * robot_columns_ + x);
            for (uint32_t k = robot_cell_starts_[cell]; k < robot_cell_starts_[cell + 1]; k++) {
                const uint32_t other = robot_cells_[k];
                // The square test first: beyond it, the distance is beyond too.
                const Enki::Vector offset = robots_[other]->pos - lens;
                if (other == index || std::abs(offset.x) > robot_reach ||
                    std::abs(offset.y) > robot_reach || offset.norm() > robot_reach)
                    continue;
                candidates.push_back(other);
            }
        }
    std::sort(candidates.begin(), candidates.end());
    for (uint32_t other : candidates) {
        Occluder occluder;
        occluder.centre = robots_[other]->pos;
        occluder.radius = body_radius;
        occluder.color = from_enki(body_color);
        near.push_back(occluder);
    }
    for (const Occluder &occluder : obstacle_occluders_)
        if ((occluder.centre - lens).norm() <= reach + occluder.radius)
            near.push_back(occluder);
    constexpr double wall_margin = 1e-6;
    const bool floor_within_walls = lens.x - reach > wall_margin && lens.y - reach > wall_margin &&
                                    lens.x + reach < arena_.width - wall_margin &&
                                    lens.y + reach < arena_.height - wall_margin;
    // A row's floor points lie within `reach` of the lens (the rays are unit
    // vectors to about 1e-16): when no coloured area's square comes that near,
    // every floor point is bare floor, as Arena::ground_color would find one
    // by one (the margin is far wider than the rounding).
    const double near_reach = reach + wall_margin;
    bool areas_within_reach = false;
    for (const GroundArea &area : arena_.areas) {
        const bool disc = area.shape == GroundArea::Shape::disc;
        const double left = disc ? area.x - area.radius : area.x;
        const double right = disc ? area.x + area.radius : area.x + area.width;
        const double bottom = disc ? area.y - area.radius : area.y;
        const double top = disc ? area.y + area.radius : area.y + area.height;
        if (lens.x + near_reach >= left && lens.x - near_reach <= right &&
            lens.y + near_reach >= bottom && lens.y - near_reach <= top) {
            areas_within_reach = true;
            break;
        }
    }
    const PixelRays &rays = pixel_rays();
    for (unsigned pixel = 0; pixel < camera_row_pixels; pixel += pixel_step) {
        // The pixel's ray turned by the robot's heading.
        Enki::Vector direction(forward.x * rays[pixel].x - forward.y * rays[pixel].y,
                               forward.y * rays[pixel].x + forward.x * rays[pixel].y);
        double nearest = reach;
        Color color = arena_.wall_color;
        bool floor = true;
        // With the whole circle of the floor's reach inside the walls, no
        // wall stands nearer (the margin is far wider than the rounding).
        if (!floor_within_walls) {
            double wall = wall_distance(arena_, lens, direction);
            if (wall < nearest) {
                nearest = wall;
                floor = false;
            }
        }
        for (const Occluder &occluder : near) {
            double hit = ray_entry(occluder, lens, direction);
            if (hit < nearest) {
                nearest = hit;
                color = occluder.color;
                floor = false;
            }
        }
        if (!floor)
            pixels[pixel] = color;
        else if (areas_within_reach)
            pixels[pixel] =
              arena_.ground_color(lens.x + reach * direction.x, lens.y + reach * direction.y);
        else
            pixels[pixel] = arena_.floor_color;
    }
}

} // namespace aseba::arena
