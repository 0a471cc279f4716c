within;
package Unimo "Components backed by unimo's runtime (external objects)"
end Unimo;
