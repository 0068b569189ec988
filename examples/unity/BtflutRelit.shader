// btflut for Unity: a material relit by btflut's include (btflut.hlsl, beside this file), every
// export kind. BtflutImporter (Editor/) builds its textures from an export folder and sets its
// properties from material.json; BtflutLight (Runtime/) sets the light per frame. The result is
// sRGB-encoded, as the reference's stored codes: linearised here for a linear-space project.
// Copyright the btflut authors; MIT licence.
Shader "btflut/Relit"
{
    Properties
    {
        _Luts ("luts.png (Texture3D)", 3D) = "" {}
        _Reference ("reference.png", 2D) = "grey" {}
        _Planes ("planes-N.png and albedo.png (Texture2DArray)", 2DArray) = "" {}
        _Weights ("weights.bin (Texture2DArray, RGBAFloat)", 2DArray) = "" {}
        _Labels ("labels.png", 2D) = "black" {}
        _LightTangent ("light direction in the tangent frame", Vector) = (0, 0, 1, 0)
        _Exposure ("exposure", Float) = 1
    }
    SubShader
    {
        Tags { "RenderType" = "Opaque" }
        Pass
        {
            HLSLPROGRAM
            #pragma vertex vert
            #pragma fragment frag
            #pragma target 4.5
            #include "UnityCG.cginc"
            #include "btflut.hlsl"
            // BtflutImporter puts a learned material's decoder here (its btflut_network.hlsl, which
            // defines BTFLUT_NETWORK) in a shader of the material's own.
            // btflut: network

            Texture3D<float4> _Luts; SamplerState sampler_Luts;
            Texture2D<float4> _Reference; SamplerState sampler_Reference;
            Texture2DArray<float4> _Planes; SamplerState sampler_Planes;
            Texture2DArray<float4> _Weights; SamplerState sampler_Weights;
            Texture2D<float4> _Labels; SamplerState sampler_Labels;
            float4 _LightTangent;
            float _Exposure;
            // From material.json (BtflutImporter): 0 luts, else the predictor's kind.
            int _Kind, _Basis, _Order, _PlaneCount, _Channels, _Albedo, _Regions;
            float _Codes, _InputCode, _OutputCode, _RgbLuts, _GreyReference, _GreyOutput;
            float _Scale[32], _Bias[32];

            struct Vertex { float4 position : POSITION; float2 uv : TEXCOORD0; };
            struct Fragment { float4 position : SV_POSITION; float2 uv : TEXCOORD0; };

            Fragment vert(Vertex v)
            {
                Fragment o;
                o.position = UnityObjectToClipPos(v.position);
                o.uv = v.uv;
                return o;
            }

            float4 frag(Fragment i) : SV_Target
            {
                uint2 pixel = uint2(i.position.xy);
                float3 light = normalize(_LightTangent.xyz);
                float3 relit;
                if (_Kind == 0)
                {
                    BtflutMaterial m;
                    m.layer = 0; m.rgbLuts = _RgbLuts > 0.5; m.greyReference = _GreyReference > 0.5;
                    m.inputCode = _InputCode; m.outputCode = _OutputCode; m.dither = true;
                    float3 value = _Reference.Sample(sampler_Reference, i.uv).rgb;
                    relit = btflutRelight(_Luts, sampler_Luts, m, value, light, pixel);
                }
                else
                {
                    BtflutPredictor p;
                    p.kind = _Kind; p.basis = _Basis; p.order = _Order; p.planes = _PlaneCount;
                    p.channels = _Channels; p.albedo = _Albedo; p.regions = _Regions; p.codes = _Codes;
                    for (int k = 0; k < 32; ++k) { p.scale[k] = _Scale[k]; p.bias[k] = _Bias[k]; }
                    p.rgbLuts = _RgbLuts > 0.5; p.greyOutput = _GreyOutput > 0.5;
                    p.outputCode = _OutputCode; p.dither = true;
            #ifdef BTFLUT_NETWORK
                    // The decoder specialised to the material, its frame at the light per fragment.
                    BtflutPrediction predicted = btflutNetworkPrediction(_Planes, sampler_Planes, i.uv,
                                                                         btflutNetworkFrame(light, float3(0, 0, 1)));
                    relit = btflutRelightPrediction(_Luts, sampler_Luts, _Planes, sampler_Planes, _Labels, sampler_Labels,
                                                    p, i.uv, light, 0, pixel, predicted);
            #else
                    relit = btflutRelight(_Luts, sampler_Luts, _Planes, sampler_Planes, _Weights, sampler_Weights,
                                          _Labels, sampler_Labels, p, i.uv, light, pixel);
            #endif
                }
                float3 colour = relit * _Exposure;
            #ifndef UNITY_COLORSPACE_GAMMA
                colour = GammaToLinearSpace(colour);
            #endif
                return float4(colour, 1);
            }
            ENDHLSL
        }
    }
}
