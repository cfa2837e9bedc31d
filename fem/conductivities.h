// Conductivity per tissue (S/m): isotropic or a symmetric positive definite 3x3 tensor.
#pragma once

#include <map>
#include <string>

#include "core/tet_mesh.h"
#include "core/vec3.h"

namespace tissuemesh::fem {

/// The tensor of an isotropic conductivity `sigma` (S/m): sigma * identity.
Mat3 isotropic(double sigma);

/// Conductivity of every tissue of a mesh, by label. Tensors in S/m, in world (RAS) axes.
struct Conductivities {
    std::map<Label, Mat3> by_label;

    /// The tensor of `tissue` (S/m); `tet` only names the element in the message.
    /// @throws InputError when the tissue has no conductivity
    const Mat3& of(Label tissue, std::size_t tet) const;
};

/// A user's table: keys are tissue names ("skull", matched case-insensitively against mesh.names), label
/// numbers ("3"), or name patterns where '*' stands for any characters ("rib_*", "vertebrae_*", "*" for
/// every other tissue); values are tensors in S/m (use isotropic() for scalars). A plain key beats any
/// pattern, a pattern with more characters other than '*' beats a shorter one.
using ConductivityTable = std::map<std::string, Mat3>;

/// Default isotropic conductivities (S/m) by tissue name, for common head tissues. Values commonly used
/// in EEG/tDCS forward modelling: scalp 0.43 and skull 0.01 (the 4-shell sphere head of issue 7, as in
/// Dannhauer et al. 2011, Hum Brain Mapp 32:1383), CSF 1.79 (Baumann et al. 1997, IEEE TBME 44:220), grey
/// matter 0.33 and white matter 0.14 (Ramon et al. 2004, Brain Topogr 16:245; as tabulated by Dannhauer et al. 2011);
/// "brain" takes the grey-matter value 0.33 (the 3/4-shell sphere models' brain). Synonyms: skin = scalp, bone = skull,
/// gm/gray = grey, wm = white.
const std::map<std::string, double>& default_head_conductivities();

/// Conductivities for every tissue present in `mesh.tet_labels`: entries of `table` first (by label
/// number or name, then by the most specific matching pattern), the remaining tissues from
/// default_head_conductivities() by name when `use_defaults`.
/// @throws InputError when a key of `table` names no tissue of the mesh (names the key and the known
///         tissues), a pattern matches none, two equally specific patterns give one tissue different values, when a
///         tissue present in the mesh has no conductivity (names it; the fix is to add it to the table), or when a
///         tensor is not symmetric positive definite or not finite
Conductivities resolve_conductivities(const TetMesh& mesh, const ConductivityTable& table, bool use_defaults = true);

} // namespace tissuemesh::fem
