#ifndef squeal_scene_scene_h
#define squeal_scene_scene_h

/**
 * @file
 * A scene: the mesh of a brake and its named parts, the one place where the
 * analyses learn what they act on. A scene makes its coarse mesh (material
 * ids = its bodies, boundary ids = its face sets) and lists the bodies with
 * their materials, the contact pairs with their sliding motion, the holds,
 * the loads, the springs and the probes. The analyses (physics, contact,
 * CEA, preload, braking) read only these lists: none of them knows a disc
 * radius, a pad position or an id number.
 *
 * make_scene() is the factory: Scene/Type = `tribobrake` gives the
 * TriboBrake of F. Massi's thesis (2006, § 3.2.1, scene/tribobrake_mesh.h),
 * `disc` its clamped disc alone.
 */

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>

#include <squeal/io/named_sets.h>
#include <squeal/parameters/parameters.h>

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace squeal
{
  namespace scene
  {
    /**
     * An anisotropic linear elastic law of a body: the stiffness tensor in
     * the material frame (physics/elastic_law.h) and the frame, Cartesian
     * (fixed axes) or cylindrical (material axes 1, 2, 3 = radial,
     * tangential, axial about an axis: a disc).
     */
    struct ElasticLaw
    {
      /// the kind of material frame
      enum class Frame
      {
        cartesian,  ///< fixed axes
        cylindrical ///< radial, tangential, axial about an axis
      };
      /// false: the body is isotropic (Body::material)
      bool anisotropic = false;
      /// the stiffness tensor in the material frame [Pa], at the body's
      /// reference modulus Body::material.youngs_modulus (the named
      /// parameter `<body>.E` scales it by E(p) / that modulus)
      dealii::SymmetricTensor<4, 3> C;
      Frame                         frame = Frame::cartesian; ///< see Frame
      /// cartesian: the columns are the material axes 1, 2, 3 in global
      /// coordinates (orthonormal)
      dealii::Tensor<2, 3> axes;
      /// cylindrical: a point of the axis [m]
      dealii::Point<3> origin;
      /// cylindrical: the axis' unit direction
      dealii::Tensor<1, 3> axis;

      /**
       * The rotation from the material to the global frame at @p x [m]:
       * columns = material axes 1, 2, 3 in global coordinates.
       * @throws std::runtime_error for a cylindrical frame at a point on its
       * axis (no radial direction there).
       */
      dealii::Tensor<2, 3>
      rotation(const dealii::Point<3> &x) const;
    };

    /** A body: the cells of one material id, of one material. */
    struct Body
    {
      std::string                name;   ///< as in outputs (`disc`, `pad`)
      dealii::types::material_id id = 0; ///< its cells' material id
      /// isotropic elastic constants [Pa, -, kg/m^3]; for an anisotropic
      /// body the density and the reference modulus of its law
      parameters::Material material;
      /// an anisotropic law (law.anisotropic), else isotropic from material
      ElasticLaw law;
      /// the body has its own Rayleigh damping (named parameters
      /// `<name>.alpha`, `<name>.beta`), else the scene's
      bool   own_damping = false;
      double alpha       = 0.; ///< own_damping: mass-proportional [1/s]
      double beta        = 0.; ///< own_damping: stiffness-proportional [s]
      /// a disc: its modes are named (n,m+-) from the axial motion of
      /// the face set @ref naming_face in the frame below
      bool disc = false;
      /// disc only: the face whose axial motion names the modes
      dealii::types::boundary_id naming_face = 0;
      dealii::Point<3>           centre; ///< disc only: a point of its axis [m]
      dealii::Tensor<1, 3>       axis;   ///< disc only: unit axis
      dealii::Tensor<1, 3> reference; ///< disc only: unit theta = 0 (the pad)
      double               inner_radius = 0.; ///< disc only [m]
      double               outer_radius = 0.; ///< disc only [m]

      /** Disc only: (r [m], theta [rad]) of @p x in the disc's frame. */
      std::pair<double, double>
      polar(const dealii::Point<3> &x) const;
    };

    /**
     * A contact pair: a slave face set pressed on a master face set that
     * slides under it. The linear friction coupling of the CEA integrates
     * on the slave face's plane (unit normal, in-plane axes plane_axes);
     * the master turns about axis through axis_point.
     */
    struct ContactPair
    {
      std::string                name;       ///< as in logs and errors
      dealii::types::boundary_id slave  = 0; ///< pad side
      dealii::types::boundary_id master = 0; ///< disc side
      /// centre of the slave face [m]
      dealii::Point<3> centre;
      /// unit normal of the slave face's plane, from the master into the
      /// slave (the direction the slave separates in)
      dealii::Tensor<1, 3> normal;
      /// orthonormal in-plane axes (plane_axes[0] x plane_axes[1] = normal)
      std::array<dealii::Tensor<1, 3>, 2> plane_axes;
      /// a point of the slave face's plane [m]
      dealii::Point<3> plane_origin;
      /// unit sliding direction of the master under the slave's centre
      /// (the linear coupling's tangent, thesis eq. 3-1)
      dealii::Tensor<1, 3> sliding;
      dealii::Tensor<1, 3> axis;       ///< unit rotation axis of the master
      dealii::Point<3>     axis_point; ///< a point of that axis [m]
      /// a length of the slave face [m] (its edge), for tolerances
      double size = 1.;
      /// Coulomb friction coefficient [-] (named parameter `<name>.mu`)
      double friction_coefficient = 0.;
      /// normal interface stiffness per area of the CEA's linear coupling
      /// [N/m^3] (named parameter `<name>.k_n`)
      double normal_stiffness = 0.;
      /// tangential (shear) interface stiffness per area of the CEA's
      /// linear coupling [N/m^3] (named parameter `<name>.k_t`): the contact
      /// layer's elastic shear on the in-plane relative displacement; 0
      /// leaves the pad free to slide in the plane
      double tangential_stiffness = 0.;

      /** The unit radial direction from the axis to the centre. */
      dealii::Tensor<1, 3>
      radial() const;
      /** In-plane coordinates [m] of @p x on the slave's plane. */
      dealii::Point<2>
      to_plane(const dealii::Point<3> &x) const;
      /** The point [m] of the plane with in-plane coordinates @p p. */
      dealii::Point<3>
      from_plane(const dealii::Point<2> &p) const;
    };

    /**
     * A bonded interface between two bodies meshed apart: the slave face
     * set's nodes are tied to the master face set (dual mortar).
     */
    struct Tie
    {
      std::string                name;       ///< as in logs and errors
      dealii::types::boundary_id slave  = 0; ///< the tied face set
      dealii::types::boundary_id master = 0; ///< the face set it follows
    };

    /** A face set held fixed in some displacement components. */
    struct Hold
    {
      std::string                name;   ///< as in logs
      dealii::types::boundary_id id = 0; ///< boundary id of its faces
      /// held components x, y, z
      std::array<bool, 3> components{{true, true, true}};
    };

    /**
     * One displacement component held at the node nearest a point (a
     * loading arm that does not let the loaded body drift where no contact
     * or spring holds it).
     */
    struct PointHold
    {
      std::string      name;          ///< as in logs
      dealii::Point<3> point;         ///< m
      unsigned int     component = 0; ///< 0, 1, 2
    };

    /**
     * A load on a face set: a total force spread uniformly over its faces,
     * or a uniform pressure, along a direction; in a braking run ramped up
     * over its own time.
     */
    struct Load
    {
      /// what sets its magnitude
      enum class Magnitude
      {
        analysis, ///< the analysis' normal force [N] (Preload, Transient)
        force,    ///< @ref value [N] in all
        pressure  ///< @ref value [Pa] on every face
      };
      std::string                name;   ///< as in logs and errors
      dealii::types::boundary_id id = 0; ///< boundary id of its faces
      /// unit direction of the force
      dealii::Tensor<1, 3> direction;
      Magnitude            magnitude = Magnitude::analysis; ///< see Magnitude
      double               value     = 0.; ///< force [N] or pressure [Pa]
      /// braking: its ramp time [s] (smooth, half-cosine); < 0: the run's
      /// Transient/Ramp duration
      double ramp = -1.;
    };

    /**
     * Springs to ground on the faces of one body, each spread over the
     * disc of radius @ref radius around its station on a plane face (a
     * Winkler layer of stiffness density k w(x) / int(w) [N/m^3], w the
     * cosine bell), acting along @ref direction. A station no node lies
     * within the radius of (or radius 0) goes to the nearest node.
     * Between two bodies (@ref to_body): each station's spring joins the
     * node of @ref body nearest it to the node of the other body nearest
     * it, along @ref direction (a pad's ear sprung against an abutment).
     */
    struct SpringSet
    {
      std::string                       name;     ///< as in logs and errors
      dealii::types::material_id        body = 0; ///< material id of the body
      std::vector<dealii::Point<3>>     stations; ///< m
      std::vector<dealii::Tensor<1, 3>> station_normals; ///< unit, per station
      dealii::Tensor<1, 3>              direction;       ///< unit
      /// N/m per spring (named parameter `<name>.k`)
      double stiffness = 0.;
      double radius    = 0.;   ///< m
      double tolerance = 1e-9; ///< m, distance of a face from a station's plane
      /// the springs join @ref body to @ref other (not to ground)
      bool to_body = false;
      /// to_body: the material id of the second body
      dealii::types::material_id other = 0;
    };

    /**
     * A lumped mass: at the node nearest a point (an accelerometer), or
     * spread evenly over a face set (a weight bonded on a face).
     */
    struct LumpedMass
    {
      std::string name;             ///< as in logs and errors
      double      mass     = 0.;    ///< kg
      bool        on_faces = false; ///< spread over a face set, else at a point
      dealii::types::boundary_id faces = 0; ///< on_faces: the face set
      dealii::Point<3>           point;     ///< else: where it sits [m]
    };

    /** A named point where results are recorded. */
    struct Probe
    {
      std::string      name;  ///< as in outputs
      dealii::Point<3> point; ///< m
    };

    /**
     * A named scalar parameter of a scene: what a sweep varies (and model
     * updating calibrates). Its name is built from the scene's items:
     * `<body>.E` [Pa], `<body>.rho` [kg/m^3], `<pair>.mu` [-],
     * `<pair>.k_n` [N/m^3], `<pair>.k_t` [N/m^3], `<springs>.k` [N/m],
     * `<mass>.m` [kg] (a lumped mass), `damping.alpha` [1/s], `damping.beta`
     * [s],
     * `<body>.alpha`, `<body>.beta` (a body with its own damping).
     */
    struct NamedParameter
    {
      std::string name;             ///< e.g. `pad.E`
      std::string unit;             ///< CSV unit suffix (`Pa`, "" if none)
      double      value    = 0.;    ///< nominal value (the file's) [unit]
      double      lowest   = 0.;    ///< smallest allowed value
      bool        low_open = false; ///< lowest itself excluded
      double      highest  = std::numeric_limits<double>::max(); ///< largest
      /// changes the mass or the structural stiffness (a reduced basis
      /// must sample it); false for friction, interface stiffness, damping
      bool structural = false;

      /**
       * The CSV column of the parameter: its name, spaces as `_`, then
       * @p qualifier, then `_` and the unit: (`pad.E`, "_min") gives
       * `pad.E_min_Pa`, `pad on disc.mu` gives `pad_on_disc.mu`.
       */
      std::string
      column(const std::string &qualifier = "") const;
    };

    /** The scene interface: see the file comment. */
    class Scene
    {
    public:
      virtual ~Scene() = default;

      /**
       * Fills the empty @p tria with the coarse mesh: material ids of the
       * bodies, boundary ids of the face sets, manifolds of curved parts.
       */
      virtual void
      make_mesh(dealii::Triangulation<3> &tria) const = 0;

      /** A one-line description for logs and errors. */
      virtual std::string
      description() const = 0;

      /**
       * The named cell, face and node sets of the coarse mesh @p tria that
       * make_mesh() built (for export: io::write_abaqus()).
       */
      virtual io::NamedSets
      named_sets(const dealii::Triangulation<3> &tria) const = 0;

      std::vector<Body>        bodies;        ///< one per material id
      std::vector<ContactPair> contact_pairs; ///< friction interfaces
      std::vector<Tie>         ties;          ///< bonded interfaces
      std::vector<Hold>        holds;         ///< fixed faces
      std::vector<PointHold>   point_holds;   ///< single held components
      std::vector<Load>        loads;         ///< the analyses' normal force
      std::vector<SpringSet>   springs;       ///< springs to ground
      std::vector<Probe>       probes;        ///< named points
      std::vector<LumpedMass>  masses;        ///< added masses
      /// Rayleigh damping of the bodies without their own: named
      /// parameters `damping.alpha` [1/s] and `damping.beta` [s]
      double damping_alpha = 0.;
      double damping_beta  = 0.; ///< see damping_alpha [s]

      /**
       * The named parameters of the scene with their nominal values, in
       * this order: per body `.E`, `.rho` (and `.alpha`, `.beta` with its
       * own damping), per contact pair `.mu`, `.k_n`, `.k_t` (and
       * `contact.mu` with two or more pairs), per spring set `.k`, per
       * lumped mass `.m`, then `damping.alpha`, `damping.beta`.
       * @throws std::runtime_error if two items give the same name.
       */
      std::vector<NamedParameter>
      parameters() const;

      /**
       * The parameter called @p name.
       * @throws std::runtime_error naming it and listing the scene's.
       */
      NamedParameter
      parameter(const std::string &name) const;

      /**
       * Makes @p value [its unit] the nominal value of the parameter called
       * @p name: the item it names changes (an anisotropic body's tensor
       * is scaled with its modulus).
       * @throws std::runtime_error as parameter() on an unknown name.
       */
      void
      set_nominal(const std::string &name, double value);

      /**
       * The linked parameters: each name with the parameters it sets
       * together. `contact.mu` (a scene with two or more contact pairs)
       * sets every pair's friction coefficient, so a sweep or a fit moves
       * them as one.
       */
      std::vector<std::pair<std::string, std::vector<std::string>>>
      links() const;

      /** Every named parameter at its nominal value. */
      parameters::ScalarPoint
      nominal_point() const;

      /**
       * The friction coefficient [-] of every contact pair at @p p, for the
       * analyses that solve one Coulomb law for all pairs (preload,
       * braking).
       * @throws std::runtime_error naming the pairs if they differ.
       */
      double
      common_friction_coefficient(const parameters::ScalarPoint &p) const;

      /**
       * The body with material id @p id.
       * @throws std::runtime_error naming the id and the scene's bodies.
       */
      const Body &
      body(dealii::types::material_id id) const;

      /**
       * The density [kg/m^3] of body @p id at @p p: `<body>.rho`.
       */
      double
      density(dealii::types::material_id     id,
              const parameters::ScalarPoint &p) const;

      /**
       * Young's modulus [Pa] of body @p id at @p p: `<body>.E`.
       */
      double
      youngs_modulus(dealii::types::material_id     id,
                     const parameters::ScalarPoint &p) const;

      /**
       * The stiffness tensor [Pa] of an anisotropic body @p id at @p x [m]
       * and the sweep point @p p, in the global frame: its law's tensor
       * rotated by ElasticLaw::rotation(x) and scaled by youngs_modulus(id,
       * p) / material.youngs_modulus.
       * @throws std::runtime_error if the body is isotropic.
       */
      dealii::SymmetricTensor<4, 3>
      stiffness_tensor(dealii::types::material_id     id,
                       const dealii::Point<3>        &x,
                       const parameters::ScalarPoint &p) const;

      /** The first body declared a disc, or nullptr. */
      const Body *
      disc() const;
    };

    /**
     * The scene of the file (Scene/Type), with its parameters copied:
     * `tribobrake`, `disc` or `mesh file` (scene/mesh_file_scene.h).
     * @throws std::runtime_error on an unknown scene type, and what the
     * scene's constructor throws.
     */
    std::unique_ptr<Scene>
    make_scene(const parameters::AllParameters &prm);

    /**
     * Checks every named parameter's value (Scene::parameters()) against its
     * physical range (NamedParameter::lowest, highest): moduli in
     * (0, 1e13] Pa, densities in (0, 1e5] kg/m^3, Rayleigh alpha in
     * [0, 1e5] 1/s and beta in [0, 1e-3] s, friction coefficients in
     * [0, 10], interface stiffnesses in [0, 1e20] N/m^3, springs in
     * (0, 1e15] N/m.
     * @throws std::runtime_error naming the parameter, its value and range.
     */
    void
    check_parameter_ranges(const Scene &scene);

    /**
     * Checks one value @p value [the parameter's unit] of the named
     * parameter @p name against its physical range (as
     * check_parameter_ranges()), for values an input gives outside the
     * scene: model updating's bounds and configurations.
     * @param entry the input that gave it, e.g. "Model updating/Parameters,
     *   upper bound of support.rho"; the error starts with it.
     * @throws std::runtime_error naming @p entry, the value and the range,
     *   or (from Scene::parameter()) an unknown name.
     */
    void
    check_parameter_value(const Scene       &scene,
                          const std::string &name,
                          double             value,
                          const std::string &entry);

    /**
     * Every point of @p sweep on @p scene: the nominal point with the first
     * parameter set to each of its values, for each value of the second
     * (second outermost).
     * @throws std::runtime_error naming the Sweep entry if a parameter is
     * not one of the scene's (listing them), both axes name the same one,
     * or a value is outside the parameter's allowed range.
     */
    std::vector<parameters::ScalarPoint>
    sweep_points(const Scene &scene, const parameters::Sweep &sweep);

    /**
     * Checks that @p scene has what Scene/Analysis @p analysis needs: the
     * preload, the preloaded CEA and braking a contact pair and a load;
     * braking a disc too when @p seeded (an initial perturbation).
     * @throws std::runtime_error naming the scene and what it lacks.
     */
    void
    check_for_analysis(const Scene       &scene,
                       const std::string &analysis,
                       bool               seeded = false);
  } // namespace scene
} // namespace squeal

#endif
