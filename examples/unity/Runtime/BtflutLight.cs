// btflut for Unity: gives a btflut/Relit material the light's direction in its tangent frame,
// each frame. On Unity's Quad (and any mesh whose u runs along the object's +x, v along +y and
// whose front faces -z) the tangent frame is (right, up, -forward). Copyright the btflut
// authors; MIT licence.
using UnityEngine;

namespace Btflut
{
    [ExecuteAlways]
    [RequireComponent(typeof(Renderer))]
    public sealed class BtflutLight : MonoBehaviour
    {
        [Tooltip("A directional light (its forward) or a point light (its position)")]
        public Light source;

        static readonly int LightTangentId = Shader.PropertyToID("_LightTangent");
        MaterialPropertyBlock properties;

        void Update()
        {
            if (source == null) return;
            Vector3 towards = source.type == LightType.Directional
                                  ? -source.transform.forward
                                  : (source.transform.position - transform.position).normalized;
            var tangent = new Vector4(Vector3.Dot(towards, transform.right), Vector3.Dot(towards, transform.up),
                                      Vector3.Dot(towards, -transform.forward), 0);
            var renderer = GetComponent<Renderer>();
            if (properties == null) properties = new MaterialPropertyBlock();
            renderer.GetPropertyBlock(properties);
            properties.SetVector(LightTangentId, tangent);
            renderer.SetPropertyBlock(properties);
        }
    }
}
